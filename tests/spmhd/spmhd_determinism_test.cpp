// The SPMHD RHS is a gather over sorted neighbour lists with a per-particle h solve: the result
// does not depend on the OpenMP thread count, and Verlet-skin lists reused across calls (while
// particles move and h changes) give the same derivatives as lists built afresh at every call,
// bit for bit (listed pairs beyond the support are skipped; the contributing pairs are summed
// in the same ascending order). The lists are rebuilt when h grows past what they serve.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

namespace sphark {
namespace {

constexpr int kNx = 24;

SpmhdOptions cleaning_resistivity() {
  SpmhdOptions o;  // examples/orszag_tang, variant cleaning+resistivity
  o.cleaning = Cleaning::Constrained;
  o.alpha_b = 1.0;
  o.h_initial = o.eta / std::sqrt(static_cast<Real>(kNx * hexagonal_rows(kNx)));
  return o;
}

struct Scene {
  ParticleSet2D p = hexagonal_lattice_unit_box(kNx, hexagonal_rows(kNx), kOrszagTangRho);
  SpmhdScheme<2> scheme;
  std::vector<Real> y0;
  Scene() : scheme(p.m, cleaning_resistivity(), unit_periodic_box()), y0(scheme.size()) {
    orszag_tang_initial_state(scheme, p, y0.data());
    // a non-zero psi, so that the cleaning terms take part
    auto psi = scalar_field(y0.data(), scheme.layout(), Field::Psi);
    for (Index a = 0; a < psi.size(); ++a) psi[a] = 0.01 * std::sin(0.37 * a);
  }
  // fresh: build the neighbour lists afresh for this call
  std::vector<Real> rhs(const std::vector<Real>& y, bool fresh = false) {
    if (fresh) scheme.drop_neighbour_lists();
    std::vector<Real> ydot(y.size());
    EXPECT_EQ(scheme.rhs(0, y.data(), ydot.data()), 0) << scheme.last_error();
    return ydot;
  }
};

// y0 with the positions moved by a compressive field of wavenumber k and strain amplitude s
// (h changes by O(s)); the largest displacement is s / (2 pi k).
// along_y = false: along x only.
std::vector<Real> compressed(const Scene& sc, Real s, int k = 1, bool along_y = true) {
  std::vector<Real> y = sc.y0;
  auto x = vector_field<2>(y.data(), sc.scheme.layout(), Field::Position);
  const Real kk = 2 * kPi * k;
  for (Index a = 0; a < x.cols(); ++a)
    x.col(a) += s * Vec<2>(std::sin(kk * x(0, a)), along_y ? std::sin(kk * x(1, a)) : 0.0) / kk;
  return y;
}

void expect_identical(const std::vector<Real>& a, const std::vector<Real>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "entry " << k;
}

TEST(SpmhdDeterminism, IndependentOfThreadCount) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  Scene one;
  const auto d1 = one.rhs(one.y0), e1 = one.rhs(compressed(one, 0.002));
  omp_set_num_threads(2);
  Scene two;
  const auto d2 = two.rhs(two.y0), e2 = two.rhs(compressed(two, 0.002));
  omp_set_num_threads(saved);
  expect_identical(d1, d2);
  expect_identical(e1, e2);
  EXPECT_EQ(one.scheme.h(), two.scheme.h());
}

TEST(SpmhdDeterminism, SkinReuseEqualsFreshBuildWhileHChanges) {
  Scene reused, fresh;  // the same calls; fresh builds new lists at every call
  reused.rhs(reused.y0);
  fresh.rhs(fresh.y0);
  const std::vector<Real> h0 = reused.scheme.h();
  for (int step = 1; step <= 3; ++step) {
    const auto y = compressed(reused, 0.004 * step);  // displacement <= 0.012 / (2 pi) < skin / 2
    const auto a = reused.rhs(y), b = fresh.rhs(y, true);
    expect_identical(a, b);
    EXPECT_EQ(reused.scheme.h(), fresh.scheme.h());
  }
  EXPECT_EQ(reused.scheme.neighbour_builds(), 1);  // reused three times
  EXPECT_EQ(fresh.scheme.neighbour_builds(), 4);
  Real dh = 0;
  for (std::size_t a = 0; a < h0.size(); ++a) dh = std::max(dh, std::abs(reused.scheme.h()[a] / h0[a] - 1));
  EXPECT_GT(dh, 1e-3);  // h did change
}

TEST(SpmhdDeterminism, RebuildsWhenHGrowsPastTheSkin) {
  Scene reused, fresh;
  reused.rhs(reused.y0);
  fresh.rhs(fresh.y0);
  const Real h_max = *std::max_element(reused.scheme.h().begin(), reused.scheme.h().end());
  // strain 0.4 along x at wavenumber 6: particles move less than half the skin (0.25 * 2 h) ...
  const auto y = compressed(reused, 0.4, 6, false);
  Real moved = 0;  // since the build at y0
  for (std::size_t k = 0; k < 2 * reused.p.size(); k += 2) {
    const std::size_t o = reused.scheme.position_offset() + k;
    moved = std::max(moved, std::hypot(y[o] - reused.y0[o], y[o + 1] - reused.y0[o + 1]));
  }
  ASSERT_LT(moved, 0.5 * 0.25 * 2 * h_max);
  // ... but h in the rarefied bands grows by more than the lists can serve
  const auto a = reused.rhs(y), b = fresh.rhs(y, true);
  const Real h_new = *std::max_element(reused.scheme.h().begin(), reused.scheme.h().end());
  EXPECT_GT(h_new, 1.1 * h_max);
  EXPECT_EQ(reused.scheme.neighbour_builds(), 2);
  EXPECT_EQ(fresh.scheme.neighbour_builds(), 2);
  expect_identical(a, b);
  EXPECT_EQ(reused.scheme.h(), fresh.scheme.h());
}

TEST(SpmhdDeterminism, NoNeighbourAllocationAfterTheFirstCall) {
  Scene sc;
  sc.rhs(sc.y0);
  const long allocations = sc.scheme.neighbours().allocations();
  EXPECT_EQ(allocations, 1);
  // shift the lattice by half a spacing (periodic: the same pairs) several times, each past
  // half the skin: every call rebuilds the lists into the existing buffers
  for (int k = 1; k <= 3; ++k) {
    std::vector<Real> y = sc.y0;
    auto x = vector_field<2>(y.data(), sc.scheme.layout(), Field::Position);
    x.row(0).array() += 0.5 * k / kNx;
    sc.rhs(y);
  }
  EXPECT_EQ(sc.scheme.neighbour_builds(), 4);
  EXPECT_EQ(sc.scheme.neighbours().allocations(), allocations);
}

// A restart (ode_system.hpp, resume_data): a scheme that never saw the run's history, handed the
// h of the interrupted run, evaluates the checkpoint's state and every later one exactly as the
// interrupted run does, although its own h solve would start elsewhere (from the lattice).
TEST(SpmhdDeterminism, ResumedSchemeContinuesBitForBit) {
  Scene run;
  const std::vector<Real> y1 = compressed(run, 0.002), y2 = compressed(run, 0.004, 2);
  run.rhs(run.y0);
  const std::vector<Real> at_checkpoint = run.rhs(y1);
  const std::vector<Real> data = run.scheme.resume_data();  // h iterates, then div v and the time of h
  const std::vector<Real> h_at_checkpoint = run.scheme.h();
  const std::size_t n = h_at_checkpoint.size();
  ASSERT_EQ(data.size(), 2 * n + 1);
  const std::vector<Real> h(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i = 0; i < n; ++i)  // the last iterates: h() is one Newton step (< tol h) past them
    ASSERT_NEAR(h[i], h_at_checkpoint[i], 1e-10 * h_at_checkpoint[i]) << i;
  ASSERT_EQ(std::vector<Real>(data.begin() + static_cast<std::ptrdiff_t>(n), data.end() - 1), run.scheme.div_v());
  const std::vector<Real> after = run.rhs(y2);

  Scene restarted;
  restarted.scheme.resume(data);
  EXPECT_EQ(restarted.scheme.h(), h);
  expect_identical(restarted.rhs(y1), at_checkpoint);  // the run's last sums and Newton step, repeated
  EXPECT_EQ(restarted.scheme.h(), h_at_checkpoint);
  expect_identical(restarted.rhs(y2), after);
  EXPECT_EQ(restarted.scheme.h(), run.scheme.h());
}

TEST(SpmhdDeterminism, ResumeRejectsSmoothingLengthsThatDoNotFit) {
  Scene sc;
  const std::size_t n = sc.scheme.h().size();
  EXPECT_THROW(sc.scheme.resume(std::vector<Real>(n - 1, 0.01)), std::invalid_argument);
  std::vector<Real> h(n, 0.01);
  h[3] = 0;
  EXPECT_THROW(sc.scheme.resume(h), std::invalid_argument);
  h[3] = std::nan("");
  EXPECT_THROW(sc.scheme.resume(h), std::invalid_argument);
  h[3] = 0.01;
  std::vector<Real> with_rate = h;  // h, div v, the time of h
  with_rate.insert(with_rate.end(), n + 1, 0.0);
  with_rate[n + 5] = std::nan("");
  EXPECT_THROW(sc.scheme.resume(with_rate), std::invalid_argument);
  sc.scheme.resume({});  // an older checkpoint without them: the scheme keeps its own start
  Scene untouched;
  expect_identical(sc.rhs(sc.y0), untouched.rhs(untouched.y0));
}

}  // namespace
}  // namespace sphark
