#pragma once
// Whether an eye sees a sphere (issue 39: opponents seen only in line of sight). Sight rays run from the eye to
// a few points of the sphere; the sphere is in sight when one of them reaches it before any solid of the world
// at that instant (the map's static solids, its movers, push mode's bodies: sense/world_rays.hpp). Other agents
// do not hide it: the world's balls are not cast against.
//
// The points, for an eye at e and a sphere of centre c and radius r, n of them (1 <= n <= kMaxSightPoints):
//   the centre c, then n - 1 points evenly spaced on the circle of radius kRimFraction * r about c that is
//   perpendicular to the line e -> c, the first on the side of world up (+x when the line is vertical).
// A ray towards a point counts as reaching the sphere when no solid lies along it nearer than where it enters
// the sphere. The centre's ray is cast alone first: a sphere in plain sight costs one ray.

#include <span>

#include "sense/world_rays.hpp"

namespace peg3d::sense {

/// The most points a sight test aims at.
inline constexpr int kMaxSightPoints = 9;
/// The rim circle's radius, as a share of the sphere's: inside it, so that a ray to a rim point enters the sphere.
inline constexpr double kRimFraction = 0.8;

/// Writes the first `n` sight points of the sphere (c, r) seen from `eye` into `out` (at least n long).
void sight_points(const Vec3& eye, const Vec3& c, double r, int n, std::span<Vec3> out);

/// Whether a sight ray from `eye` to one of the first `points` sight points of the sphere (c, r) reaches it before
/// any solid of `world` (its balls ignored). An eye inside the sphere sees it. No allocation.
bool line_of_sight(const WorldAtInstant& world, const Vec3& eye, const Vec3& c, double r, int points);

}  // namespace peg3d::sense
