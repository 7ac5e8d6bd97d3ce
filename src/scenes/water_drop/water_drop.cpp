#include "sphark/scenes/water_drop/water_drop.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphark/initial/lattice_2d.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/tait_eos.hpp"

namespace sphark {

SemiAxes measure_semi_axes(const Real* positions, std::size_t n) { return measure_semi_axes(Communicator{}, positions, n); }

SemiAxes measure_semi_axes(const Communicator& comm, const Real* positions, std::size_t n) {
  Vec<2> c = Vec<2>::Zero();
  for (std::size_t a = 0; a < n; ++a) c += Eigen::Map<const Vec<2>>(positions + 2 * a);
  Real sums[3] = {c.x(), c.y(), static_cast<Real>(n)};
  comm.allreduce(sums, 3, ReduceOp::Sum);  // serially: unchanged
  c = Vec<2>(sums[0], sums[1]) / sums[2];
  Real s[2] = {0, 0};
  for (std::size_t a = 0; a < n; ++a) {
    const Vec<2> d = Eigen::Map<const Vec<2>>(positions + 2 * a) - c;
    s[0] += d.x() * d.x();
    s[1] += d.y() * d.y();
  }
  comm.allreduce(s, 2, ReduceOp::Sum);
  // a uniform ellipse has <x^2> = a^2 / 4
  return {2 * std::sqrt(s[0] / sums[2]), 2 * std::sqrt(s[1] / sums[2])};
}

namespace {
template <class Kernel>
class WcsphModelOf final : public WcsphModel {
 public:
  WcsphModelOf(std::size_t n, WcsphParams<2> p) : sys_(n, std::move(p)) {}
  OdeSystem& system() override { return sys_; }
  const StateLayout& layout() const override { return sys_.layout(); }
  WcsphDiagnostics<2> diagnostics(Real t, const Real* y) override { return wcsph_diagnostics(sys_, t, y); }
  ParticleFrame frame(Real t, const Real* y) override { return frame_.build(sys_, t, y); }
  long neighbour_builds() const override { return sys_.neighbour_builds(); }
  void distribute(Communicator comm, std::vector<std::int64_t> ids) override { sys_.distribute(std::move(comm), std::move(ids)); }
  void set_particles(std::vector<std::int64_t> ids) override { sys_.set_particles(std::move(ids)); }

 private:
  WcsphSystem<2, Kernel> sys_;
  WcsphFrame frame_;
};

std::unique_ptr<WcsphModel> make_model(const std::string& kernel, std::size_t n, WcsphParams<2> p) {
  return with_kernel<2>(kernel, [&](auto tag) -> std::unique_ptr<WcsphModel> {
    return std::make_unique<WcsphModelOf<typename decltype(tag)::type>>(n, std::move(p));
  });
}

void require_positive(Real v, const char* what) {
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be a positive number");
}
}  // namespace

std::vector<Real> water_drop_absolute_tolerances(const WaterDrop& drop, Real atol) {
  const WaterDropConfig& c = drop.config;
  const Real vscale = std::max(c.amplitude, c.omega) * c.radius;
  return per_field_tolerance(drop.model->layout(),
                             {{Field::Position, atol * c.radius},
                              {Field::Velocity, atol * vscale},
                              {Field::Density, atol * c.rho0},
                              {Field::Psi, atol * c.rho0 * c.sound_speed * vscale}},
                             atol);
}

std::vector<std::string> wcsph_kernel_names() { return kernel_names<2>(); }

WaterDrop make_water_drop(const WaterDropConfig& cfg) {
  require_positive(cfg.radius, "radius");
  require_positive(cfg.spacing, "spacing");
  require_positive(cfg.rho0, "rho0");
  require_positive(cfg.sound_speed, "sound speed");
  require_positive(cfg.h_factor, "h factor");
  require_positive(cfg.cfl, "cfl");
  if (cfg.spacing > 0.5 * cfg.radius) throw std::invalid_argument("spacing must be at most half the radius");

  // Square lattice offset by half a spacing, points strictly inside the disc.
  const ParticleSet2D lattice = disc_square_lattice(cfg.radius, cfg.spacing, cfg.rho0);
  std::vector<Vec<2>> pts(lattice.size());
  for (std::size_t a = 0; a < pts.size(); ++a) pts[a] = Vec<2>(lattice.x[2 * a], lattice.x[2 * a + 1]);

  WcsphParams<2> p;
  p.rho0 = cfg.rho0;
  p.sound_speed = cfg.sound_speed;
  p.mass = cfg.rho0 * cfg.spacing * cfg.spacing;
  p.h = cfg.h_factor * cfg.spacing;  // seed 000, eq. (5): h = eta (m / rho)^(1/2) = eta dx
  p.alpha = cfg.alpha;
  p.delta = cfg.delta;
  p.diffusion_correction = cfg.diffusion_correction;
  p.cleaning = cfg.cleaning;
  p.clean_sigma = cfg.clean_sigma;
  p.cfl = cfg.cfl;
  p.skin_fraction = cfg.skin;
  const Real w2 = cfg.omega * cfg.omega;
  p.body_force = [w2](const Vec<2>& x) -> Vec<2> { return -w2 * x; };
  p.body_potential = [w2](const Vec<2>& x) -> Real { return 0.5 * w2 * x.squaredNorm(); };

  WaterDrop drop{cfg, make_model(cfg.kernel, pts.size(), p), {}, EllipticDrop(cfg.radius, cfg.amplitude, cfg.omega)};
  const StateLayout& L = drop.model->layout();
  drop.y0.assign(L.size(), 0.0);
  auto x = vector_field<2>(drop.y0.data(), L, Field::Position);
  auto v = vector_field<2>(drop.y0.data(), L, Field::Velocity);
  auto rho = scalar_field(drop.y0.data(), L, Field::Density);
  for (std::size_t a = 0; a < pts.size(); ++a) {
    x.col(a) = pts[a];
    v.col(a) = Vec<2>(-cfg.amplitude * pts[a].x(), cfg.amplitude * pts[a].y());
    rho[a] = cfg.rho0;
    if (cfg.exact_initial_pressure) {
      const Real p0 = cfg.rho0 * drop.exact.central_pressure_over_rho(drop.exact.at(0.0));
      const Real pa = p0 * (1 - pts[a].squaredNorm() / (cfg.radius * cfg.radius));
      rho[a] = tait_density(pa, cfg.rho0, cfg.sound_speed);
    }
  }
  return drop;
}

}  // namespace sphark
