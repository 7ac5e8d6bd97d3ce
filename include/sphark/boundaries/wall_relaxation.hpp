#pragma once
// Relaxation next to a wall (the role ALARIC plays in seed 004, §7): the particles marked
// movable take gradient steps on the node density (as relax_uniform) where n includes the ghosts
// of the wall, regenerated at every iteration; the others stay fixed and only contribute to n.
//
// Why: a set relaxed in a periodic box and then cut by a wall has glass statistics across the
// cut, but an inner particle at s and its own ghost at psi(s) ~ -s can be arbitrarily close, so
// the mirrored layer has an excess of close pairs and n rises by ~2-4% at the wall for ANY map
// (even a flat wall). Relaxing with the ghosts in the loop removes those pairs, as the paper does.
// The map used in the loop is a choice; the static tests use Psi (the paper's Fig. 7 shows its
// inner n flat with Psi and perturbed with Psi0) and report the mirror-relaxed set as well.
#include <optional>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/boundaries/relaxation.hpp"

namespace sphark {

// x: D x n positions inside the wall's fluid side. movable[i] != 0 for particles that move.
// box: periodic axes that are physical (e.g. the cylinder's axis), nullopt if none.
// Stops when std(n)/<n> over the movable particles <= opt.tolerance or after max_iterations;
// throws StopRequested (run/signals.hpp) at the next iteration after SIGINT/SIGTERM.
template <int D>
RelaxReport relax_near_wall(std::vector<Real>& x, const Wall<D>& wall, GhostMap map, Real h,
                            const std::vector<char>& movable, const std::optional<PeriodicBox<D>>& box,
                            const RelaxOptions& opt = {});

}  // namespace sphark
