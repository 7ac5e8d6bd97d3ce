#pragma once
// Wall geometries with local coordinates (s, u, v) (seed 004, §3): s is the signed distance to
// the wall (s < 0 on the fluid side), u, v label the normal line through the point, and the
// Jacobian J(s, u, v) of (s, u, v) -> x, given up to a factor independent of s (only ratios
// J(s)/J(psi) at equal u, v enter the map, seed 004 eq. 13).
//
//   wall        rho (radial coord.)  u, v                 J                 seed 004
//   Plane       -                    tangential coords     1                 eq. (14)
//   Cylinder    R + s (inside)       azimuth, axial z      rho               eqs. (17)-(18)
//   Sphere      R + s (inside)       azimuth, polar angle  rho^2 sin(v)      eqs. (22)-(23)
//   Torus       a + s (inside)       poloidal, toroidal    rho (R+rho cos u) eqs. (26)-(27)
// For fluid outside an obstacle rho = rho0 - s. Cylinder<2> is the circle (2D cross-section).
// Cylinder and torus axes are along z, through `centre`.
#include <cmath>
#include <variant>

#include "sphark/boundaries/maps.hpp"
#include "sphark/core/types.hpp"

namespace sphark {

// What ghost placement needs at a point: s, the unit normal towards s > 0, and cos(u) (torus).
template <int D>
struct WallPoint {
  Real s = 0;
  Vec<D> normal = Vec<D>::Zero();
  Real cos_u = 0;
};

struct WallCoords {
  Real s = 0, u = 0, v = 0;
};

template <int D>
struct Plane {
  Vec<D> point = Vec<D>::Zero();
  Vec<D> normal = Vec<D>::UnitX();  // unit, pointing out of the fluid (towards s > 0)

  WallPoint<D> locate(const Vec<D>& x) const { return {(x - point).dot(normal), normal, 0}; }
  WallCoords coordinates(const Vec<D>& x) const;
  Real jacobian(Real, Real, Real) const { return 1; }
  Real psi_max(Real) const { return kInfinity; }
  MapResult map(const WallPoint<D>& p) const { return mirror_map(p.s); }  // seed 004, eq. (15)
  MapResult map(Real s, Real, Real) const { return mirror_map(s); }
};

template <int D>
struct Cylinder {
  static_assert(D == 2 || D == 3, "Cylinder: the circle in 2D, the z-axis cylinder in 3D");
  Vec<D> centre = Vec<D>::Zero();
  Real R = 1;
  FluidSide side = FluidSide::Inside;

  WallPoint<D> locate(const Vec<D>& x) const {
    Vec<D> d = x - centre;
    if constexpr (D == 3) d[2] = 0;
    const Real rho = d.norm();
    const Vec<D> e = rho > 0 ? Vec<D>(d / rho) : Vec<D>(Vec<D>::UnitX());
    const Real sg = side_sign(side);
    return {sg * (rho - R), sg * e, 0};
  }
  WallCoords coordinates(const Vec<D>& x) const {
    const Vec<D> d = x - centre;
    const Real rho = std::hypot(d[0], d[1]);
    return {side_sign(side) * (rho - R), std::atan2(d[1], d[0]), D == 3 ? d[D - 1] : 0};
  }
  Real jacobian(Real s, Real, Real) const { return R + side_sign(side) * s; }  // eq. (18)
  Real psi_max(Real) const { return side == FluidSide::Inside ? kInfinity : R; }
  MapResult map(const WallPoint<D>& p) const { return cylinder_map(p.s, R, side); }  // eq. (21)
  MapResult map(Real s, Real, Real) const { return cylinder_map(s, R, side); }
};

struct Sphere {
  Vec<3> centre = Vec<3>::Zero();
  Real R = 1;
  FluidSide side = FluidSide::Inside;

  WallPoint<3> locate(const Vec<3>& x) const {
    const Vec<3> d = x - centre;
    const Real rho = d.norm();
    const Vec<3> e = rho > 0 ? Vec<3>(d / rho) : Vec<3>(Vec<3>::UnitX());
    const Real sg = side_sign(side);
    return {sg * (rho - R), sg * e, 0};
  }
  WallCoords coordinates(const Vec<3>& x) const {
    const Vec<3> d = x - centre;
    const Real rho = d.norm();
    return {side_sign(side) * (rho - R), std::atan2(d[1], d[0]), rho > 0 ? std::acos(d[2] / rho) : 0};
  }
  Real jacobian(Real s, Real, Real) const {  // eq. (23); the sin(v) factor cancels in eq. (13)
    const Real rho = R + side_sign(side) * s;
    return rho * rho;
  }
  Real psi_max(Real) const { return side == FluidSide::Inside ? kInfinity : R; }
  MapResult map(const WallPoint<3>& p) const { return sphere_map(p.s, R, side); }  // eq. (25)
  MapResult map(Real s, Real, Real) const { return sphere_map(s, R, side); }
};

struct Torus {
  Vec<3> centre = Vec<3>::Zero();
  Real R = 3;  // major radius
  Real a = 1;  // minor radius
  FluidSide side = FluidSide::Inside;

  WallPoint<3> locate(const Vec<3>& x) const {
    const Vec<3> d = x - centre;
    const Real rxy = std::sqrt(d[0] * d[0] + d[1] * d[1]);
    const Real ex = rxy > 0 ? d[0] / rxy : 1, ey = rxy > 0 ? d[1] / rxy : 0;
    const Real dr = rxy - R, r = std::sqrt(dr * dr + d[2] * d[2]);
    const Real c = r > 0 ? dr / r : 1, sn = r > 0 ? d[2] / r : 0;  // cos u, sin u
    const Real sg = side_sign(side);
    return {sg * (r - a), Vec<3>(sg * c * ex, sg * c * ey, sg * sn), c};
  }
  WallCoords coordinates(const Vec<3>& x) const {
    const Vec<3> d = x - centre;
    const Real dr = std::hypot(d[0], d[1]) - R;
    return {side_sign(side) * (std::hypot(dr, d[2]) - a), std::atan2(d[2], dr), std::atan2(d[1], d[0])};
  }
  Real jacobian(Real s, Real u, Real) const {  // eq. (27): J = rho (R + rho cos u)
    const Real rho = a + side_sign(side) * s;
    return rho * (R + rho * std::cos(u));
  }
  // The ghost must stay on the fluid's side of the torus axis (inside) or of the tube's centre
  // line (outside).
  Real psi_max(Real u) const {
    if (side == FluidSide::Outside) return a;
    const Real c = std::cos(u);
    return c < 0 ? R / -c - a : kInfinity;
  }
  MapResult map(const WallPoint<3>& p) const { return torus_map(p.s, a, R, p.cos_u, side); }
  MapResult map(Real s, Real u, Real) const { return torus_map(s, a, R, std::cos(u), side); }
};

template <int D>
WallCoords Plane<D>::coordinates(const Vec<D>& x) const {
  const Vec<D> d = x - point;
  Vec<D> t1 = Vec<D>::Zero();
  if constexpr (D >= 2) {
    t1[0] = -normal[1];
    t1[1] = normal[0];
    if (t1.norm() == 0) t1 = Vec<D>::UnitX();
    t1.normalize();
  }
  Real v = 0;
  if constexpr (D == 3) v = d.dot(normal.cross(t1));
  return {d.dot(normal), D >= 2 ? d.dot(t1) : 0, v};
}

template <int D>
struct WallTypes;
template <>
struct WallTypes<2> {
  using type = std::variant<Plane<2>, Cylinder<2>>;
};
template <>
struct WallTypes<3> {
  using type = std::variant<Plane<3>, Cylinder<3>, Sphere, Torus>;
};
// Any wall of dimension D; ghost generation dispatches once per call, not per particle.
template <int D>
using Wall = typename WallTypes<D>::type;

// The density-preserving map of any wall by the generic quadrature + Newton solver
// (generic_map.hpp); used to check the closed forms and for walls without one.
MapResult generic_wall_map(const Wall<3>& wall, Real s, Real u, Real v);
MapResult generic_wall_map(const Wall<2>& wall, Real s, Real u, Real v);

}  // namespace sphark
