#pragma once
// RAII holders for the SUNDIALS objects a stepper owns. Private to src/integrate/.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <arkode/arkode_mristep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include <memory>
#include <stdexcept>
#include <type_traits>

#include "sphark/core/types.hpp"
#include "sphark/parallel/sundials_vector.hpp"

namespace sphark::detail {

struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct ErkMemDeleter {
  void operator()(void* mem) const { ERKStepFree(&mem); }
};
struct ArkMemDeleter {
  void operator()(void* mem) const { ARKStepFree(&mem); }
};
struct MriMemDeleter {
  void operator()(void* mem) const { MRIStepFree(&mem); }
};
struct InnerStepperDeleter {
  void operator()(MRIStepInnerStepper s) const { MRIStepInnerStepper_Free(&s); }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using ErkMemPtr = std::unique_ptr<void, ErkMemDeleter>;
using ArkMemPtr = std::unique_ptr<void, ArkMemDeleter>;
using MriMemPtr = std::unique_ptr<void, MriMemDeleter>;
using InnerStepperPtr = std::unique_ptr<std::remove_pointer_t<MRIStepInnerStepper>, InnerStepperDeleter>;

// The context of a stepper: with the MPI communicator of a distributed run, else none.
inline ContextPtr make_context(const Communicator& comm = {}) {
  SUNContext ctx = nullptr;
  if (create_sundials_context(comm, &ctx) != 0 || ctx == nullptr)
    throw std::runtime_error("SUNContext_Create failed");
  return ContextPtr(ctx);
}

// An N_Vector viewing memory we own (no copy, not freed by SUNDIALS): N_VMake_Serial, or
// N_VMake_Parallel over an MPI communicator (collective).
inline VectorPtr make_view(std::size_t n, Real* data, SUNContext ctx, const Communicator& comm = {}) {
  N_Vector v = make_vector_view(comm, n, data, ctx);
  if (v == nullptr) throw std::runtime_error(comm.distributed() ? "N_VMake_Parallel failed" : "N_VMake_Serial failed");
  return VectorPtr(v);
}

}  // namespace sphark::detail
