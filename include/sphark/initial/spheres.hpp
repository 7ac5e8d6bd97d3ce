#pragma once
// Initial particle positions for 3D spheres (issue #15: cold uniform collapse, Evrard collapse;
// issue #16: the cloud core in its periodic box of ambient gas). Positions: 3 values per
// particle (the state's layout); all particles of a set have the same mass.
//
//  uniform_sphere   a close-packed lattice cut by the ball |x| < R, its spacing bisected so
//                   that the count is as close to the request as the lattice allows
//                   (placement: sphark/initial/close_packed.hpp), or `random` (uniform in the
//                   ball, fixed seed, exactly the requested count)
//  evrard_sphere    rho = M / (2 pi R^2 r) (Evrard 1988): the uniform sphere mapped radially by
//                   r -> R (r / R)^(3/2), so that M(<r) = M (r / R)^2 (the enclosed fraction of
//                   a uniform sphere at r_u = R (r / R)^(2/3) is (r_u / R)^3 = (r / R)^2);
//                   the lattice becomes anisotropic near the centre (tangential spacing x (r/R)^(1/2))
//  sphere_in_box    the sphere on an fcc lattice plus ambient gas filling the periodic cube of
//                   side L around it (sphere cut out) at 1/contrast of its density with the same
//                   particle mass (Phantom's setup_sphereinbox). The ambient fcc must tile the
//                   cube exactly (k cells per side), so the ambient spacing is L / k and the
//                   sphere's is L / (k contrast^(1/3)): the density ratio of the two lattices is
//                   exactly `contrast` in both fits:
//                     BoxFit::exact_side     the cube is exactly L; the sphere count is the
//                                            nearest k allows (within (1 +- 1/(2k))^3 of the request)
//                     BoxFit::nearest_count  the sphere as uniform_sphere (count nearest the
//                                            request); the side becomes k a_ambient, within a
//                                            factor 1 +- 1/(2k) of L
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/initial/close_packed.hpp"

namespace sphark {

struct SphereSpec {
  std::size_t particles = 0;  // requested count
  Real radius = 1;
  Real mass = 1;
  CloseLattice lattice = CloseLattice::fcc;
  bool random = false;        // uniform random placement instead of a lattice
  std::uint64_t seed = 1;     // for random placement (std::mt19937_64)
};

struct ParticlePlacement {
  std::vector<Real> x;        // 3 per particle
  Real particle_mass = 0;
  Real spacing = 0;           // lattice nearest-neighbour distance before any stretch (random: (m/rho)^(1/3) of the mean density)
  std::size_t size() const { return x.size() / 3; }
};

// Throws std::invalid_argument unless particles >= 1, radius > 0, mass > 0.
ParticlePlacement uniform_sphere(const SphereSpec& spec);

// r -> R (r / R)^(3/2) for every particle (in place): a uniform sphere of radius R becomes
// rho proportional to 1/r with the same total mass and radius.
void stretch_to_inverse_r(std::vector<Real>& x, Real radius);

ParticlePlacement evrard_sphere(const SphereSpec& spec);

struct SphereInBox {
  ParticlePlacement sphere;   // |x| < R, total mass M
  std::vector<Real> ambient;  // |x| >= R inside [-L/2, L/2)^3, fcc, periodic; same particle mass
  Real side = 0;              // L
  std::size_t ambient_cells = 0;  // k
  Real ambient_spacing = 0;   // nearest-neighbour distance of the ambient lattice
  // lattice densities (particle mass x number density): their ratio is the contrast exactly
  Real sphere_lattice_density = 0, ambient_lattice_density = 0;
};

enum class BoxFit { exact_side, nearest_count };

// Throws std::invalid_argument unless particles >= 1, R > 0, M > 0, side > 2R, contrast >= 1.
// spec.lattice is the sphere's lattice (the ambient is fcc: it must tile the cube); spec.random
// is not supported here (throws).
SphereInBox sphere_in_box(const SphereSpec& spec, Real side_over_radius = 4, Real density_contrast = 30,
                          BoxFit fit = BoxFit::exact_side);

}  // namespace sphark
