#pragma once
// Bullet's view of an arena's terrain: one bounding-volume hierarchy per mesh over the Arena's own arrays.
// Building it is the costly part of a collision world on a large terrain (about a second for a million
// triangles), so the Arena builds it once, on the first request, and every CollisionWorld over that Arena
// shares it read-only, in any thread: Bullet's sweeps and contact tests only read a static shape.
// World-internal: only arena.cpp and collision_world.cpp include Bullet through this header.

#include <memory>
#include <vector>

#include <btBulletCollisionCommon.h>

#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

struct TerrainShapes {
  explicit TerrainShapes(const std::vector<TriangleMesh>& meshes) {
    for (const TriangleMesh& m : meshes) {
      // Bullet reads the Arena's arrays in place; it never writes them.
      arrays.push_back(std::make_unique<btTriangleIndexVertexArray>(
          int(m.faces.size()), const_cast<int*>(m.faces.front().data()), int(sizeof(m.faces[0])),
          int(m.vertices.size()), const_cast<btScalar*>(m.vertices.front().data()), int(sizeof(Vec3))));
      shapes.push_back(std::make_unique<btBvhTriangleMeshShape>(arrays.back().get(), /*useQuantizedAabbCompression=*/true));
    }
  }

  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> arrays;
  std::vector<std::unique_ptr<btBvhTriangleMeshShape>> shapes;  // shapes[i] is meshes[i]
};

}  // namespace peg3d::world
