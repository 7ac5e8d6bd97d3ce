#pragma once
// Close-packed lattices (face-centred cubic and hexagonal close-packed) for 3D initial
// conditions. Both have nearest-neighbour distance d, 12 nearest neighbours, number density
// sqrt(2) / d^3 and covering radius d / sqrt(2) (the octahedral holes: every point of space lies
// within d / sqrt(2) of a lattice site, so a lattice cut by a ball of radius r holds between
// n V(r - d/sqrt 2) and n V(r + d/sqrt 2) sites; Conway & Sloane, "Sphere Packings", ch. 1).
//
// Placement. The origin is an inversion centre of the generated set, so a lattice cut by a
// ball about the origin has its centre of mass there to round-off:
//   fcc: sites a (i, j, k) / 2 with i + j + k even, a = sqrt(2) d (cubic cell side), shifted by
//        minus (a/4, a/4, 0), the mid-point of a nearest pair (an inversion centre whose site
//        symmetry, order 8, is lower than a site's 48: a ball gains sites in smaller shells, so
//        its count can be set closer to a request).
//   hcp: layers A, B, A, ... of triangular nets (spacing d) a height d sqrt(2/3) apart, B shifted
//        by (d/2, d sqrt(3)/6); the whole set shifted by minus the midpoint of an A-B nearest
//        pair, (d/4, d sqrt(3)/12, d sqrt(2/3)/2), which is an inversion centre of hcp.
// Positions are returned as 3 values per particle (x0, y0, z0, x1, ...), the layout of the
// state's position field.
#include <cstddef>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

enum class CloseLattice { fcc, hcp };

inline Real close_packed_number_density(Real spacing) { return 1.4142135623730951 / (spacing * spacing * spacing); }
// nearest-neighbour distance d of a close-packed lattice of number density n: (sqrt(2) / n)^(1/3)
Real close_packed_spacing(Real number_density);
inline Real close_packed_covering_radius(Real spacing) { return spacing / 1.4142135623730951; }

// Sites with |x| < radius, in a fixed order (layer by layer).
std::vector<Real> close_packed_ball(CloseLattice lattice, Real spacing, Real radius);
// Their number (nothing stored).
std::size_t close_packed_ball_count(CloseLattice lattice, Real spacing, Real radius);

// fcc sites of a periodic cube [-side/2, side/2)^3 with `cells` cubic cells along each side
// (4 cells^3 sites, cubic cell a = side / cells, d = a / sqrt(2)), minus those with
// |x| < exclude_radius. Periodic: the lattice continues across every face unchanged.
std::vector<Real> fcc_periodic_cube(Real side, std::size_t cells, Real exclude_radius = 0);

}  // namespace sphark
