#pragma once
// A complete sparse LU factorisation of the Newton matrix (Trilinos Amesos,
// KLU) used as GMRES's preconditioner: 'fluid solver/preconditioner = lu'.
// While it is fresh GMRES converges in one or two iterations; reused over the next
// Newton steps and time steps (VansSolver::solve_linear rebuilds it when the
// iteration count grows), each application costs two triangular solves. It
// pivots, so it solves the systems on which ILU(k), alone or as ML's smoother,
// breaks down on zero or tiny pivots (water at rest in a column seven or more
// cells across), at a factorisation cost that grows faster than the mesh:
// doc/fluid.md, "Linear solver", says up to what size it pays.

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

namespace sluice
{
  class FactorizedPreconditioner : public dealii::TrilinosWrappers::PreconditionBase
  {
  public:
    /// Factorises the matrix now; the factors are a copy, so the matrix may
    /// change afterwards (the preconditioner then becomes an approximation).
    explicit FactorizedPreconditioner(const dealii::TrilinosWrappers::SparseMatrix &matrix)
      : control(1, 0.)
      , direct(control,
               dealii::TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"))
    {
      direct.initialize(matrix);
    }

    void vmult(dealii::TrilinosWrappers::MPI::Vector       &dst,
               const dealii::TrilinosWrappers::MPI::Vector &src) const override
    {
      direct.solve(dst, src);
    }

  private:
    // Amesos's solve is not const, though it leaves the factors unchanged.
    mutable dealii::SolverControl                control;
    mutable dealii::TrilinosWrappers::SolverDirect direct;
  };
} // namespace sluice
