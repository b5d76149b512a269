#pragma once
// What a mesh file declares, checked against what it holds before any importer sees it. A few hundred bytes
// whose header promises four billion vertices make an importer reserve tens of gigabytes; a glTF node that
// is its own grandchild, or a chain of 100 000 nodes, makes it recurse without end; a glTF buffer may name
// /dev/zero or ../../secret. These checks refuse such files with a message naming the declaration; the
// bounded import (triangle_mesh.cpp) is the second line for whatever they miss.

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "core/error.hpp"

namespace peg3d::world {

/// A mesh file that cannot be used; what() says why, naming the file.
class MeshError : public InputError {
 public:
  using InputError::InputError;
};

/// The formats peg3d imports, as a message lists them.
inline constexpr std::string_view kAcceptedMeshFormats = "OBJ (.obj), STL (.stl), PLY (.ply), OFF (.off), glTF 2 (.gltf, .glb), 3DS (.3ds)";
/// Largest mesh file read, bytes (a terrain of several million triangles is well below).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;

/// True for the (lower-cased) extensions of kAcceptedMeshFormats, with the dot: ".obj", ".glb", ...
bool is_accepted_mesh_extension(std::string_view extension);

/// Checks a mesh file of an accepted format: PLY element counts, OFF counts and binary STL facet counts
/// against the file's size; glTF buffers, views and accessors against their data, its node hierarchy (a
/// tree, at most 64 deep) and its external files (relative, inside the mesh's folder, regular); 3DS chunk
/// lengths and vertex and face counts. Throws MeshError naming the file and the offending declaration.
void check_mesh_declarations(const std::filesystem::path& file);

/// True if `reference`, a file a mesh names (a glTF buffer, an OBJ material library), may be opened: a
/// regular file inside the folder of `mesh` (no absolute path, no "..", no device or FIFO).
bool is_safe_mesh_reference(const std::filesystem::path& mesh, const std::filesystem::path& reference);

}  // namespace peg3d::world
