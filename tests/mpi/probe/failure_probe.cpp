// failure_probe MODE: how a distributed program ends when its last rank fails (run under
// mpirun by tests/mpi/CMakeLists.txt, checked by run_probe.cmake: exit code and message).
//   collective  the failure is detected at a collective check: rank 0 prints "error: rank r:
//               ..." once, every rank exits 1, nothing aborts;
//   stepper     the last rank's RHS throws inside Stepper::advance: every rank stops with the
//               same failure (exit 3), rank 0 prints the reason naming that rank;
//   throw       the last rank throws between collectives: it prints "rank r of N: ..." and
//               MPI_Abort ends every rank with exit code 1 (the others wait in a collective);
//   hang        the last rank waits in a barrier while the others wait for its message: the
//               exchange times out (SPHARK_MPI_TIMEOUT) and aborts every rank, no hang.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sphark/parallel/mpi_session.hpp"

namespace {

using namespace sphark;

class Decay final : public OdeSystem {  // y' = -y on every rank; the last rank's RHS throws at t > 0.5
 public:
  explicit Decay(bool fails) : fails_(fails) {}
  std::size_t size() const override { return 3; }
  int rhs(Real t, const Real* y, Real* ydot) override {
    if (fails_ && t > 0.5) throw std::runtime_error("injected failure");
    for (int k = 0; k < 3; ++k) ydot[k] = -y[k];
    return 0;
  }

 private:
  bool fails_;
};

int stepper_mode(const Communicator& world) {
  Decay sys(world.rank() == world.size() - 1);
  StepperOptions o;
  o.communicator = world;
  std::vector<Real> y(3, 1.0);
  auto stepper = make_stepper(sys, o, 0.0, y.data());
  Real t = 0;
  if (stepper->advance(2.0, y.data(), t) != AdvanceStatus::Failed) return 0;
  if (world.rank() == 0) std::fprintf(stderr, "failed at t=%g: %s\n", t, stepper->failure_reason().c_str());
  return 3;
}

int probe(const Communicator& world, const std::string& mode) {
  const bool last = world.rank() == world.size() - 1;
  if (mode == "collective") world.check(!last, "injected failure");
  if (mode == "stepper") return stepper_mode(world);
  if (mode == "throw") {
    if (last) throw std::runtime_error("injected failure");
    world.barrier();  // never completes: the last rank aborts the run
  }
  if (mode == "hang") {
    if (last) {
      world.barrier();  // the others never get here
    } else {
      double value = 0;
      world.exchange({}, {{world.size() - 1, &value, sizeof value}});
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  const std::string mode = argc > 1 ? argv[1] : "";
  return mpi.run([&](const Communicator& world) { return probe(world, mode); });
}
