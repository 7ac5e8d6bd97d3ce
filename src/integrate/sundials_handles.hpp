#pragma once
// RAII holders for the SUNDIALS objects a stepper owns. Private to src/integrate/.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include <memory>
#include <stdexcept>
#include <type_traits>

#include "sphark/core/types.hpp"

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

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using ErkMemPtr = std::unique_ptr<void, ErkMemDeleter>;
using ArkMemPtr = std::unique_ptr<void, ArkMemDeleter>;

inline ContextPtr make_context() {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr)
    throw std::runtime_error("SUNContext_Create failed");
  return ContextPtr(ctx);
}

// A serial N_Vector viewing memory we own (N_VMake_Serial: no copy, not freed by SUNDIALS).
inline VectorPtr make_view(std::size_t n, Real* data, SUNContext ctx) {
  N_Vector v = N_VMake_Serial(static_cast<sunindextype>(n), data, ctx);
  if (v == nullptr) throw std::runtime_error("N_VMake_Serial failed");
  return VectorPtr(v);
}

}  // namespace sphark::detail
