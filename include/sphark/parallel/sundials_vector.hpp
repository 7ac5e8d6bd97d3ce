#pragma once
// SUNDIALS objects over a Communicator: a serial one gives exactly the serial objects
// (N_VMake_Serial, a context without a communicator); an MPI one gives SUNDIALS' own parallel
// vector (N_VMake_Parallel: each rank holds its local entries, norms and dot products are
// reduced over the ranks), so ARKODE's error norms and step choices are global.
#include <cstddef>

#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include "sphark/core/types.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

// A vector viewing n local values at data (not copied, not freed by N_VDestroy). With MPI the
// global length is the sum of n over the ranks (collective: every rank calls it).
N_Vector make_vector_view(const Communicator& comm, std::size_t n, Real* data, SUNContext ctx);

// Replaces the vector's weighted RMS norm (the one ARKODE steers its steps with) by one whose
// value depends only on the set of entries, not on their order nor on how they are split over
// ranks (exact fixed-point sum, rounded once: src/parallel/reproducible_norm.cpp). Clones of
// the vector inherit it. Every distributed stepper uses it; a serial run that sets
// StepperOptions::reproducible_norms takes exactly the steps of a run on any number of ranks.
void make_norms_reproducible(N_Vector v);

// SUNContext_Create(&MPI_Comm, ...) or SUNContext_Create(nullptr, ...) when serial; 0 on success.
int create_sundials_context(const Communicator& comm, SUNContext* ctx);

}  // namespace sphark
