#pragma once
// Sparse Cholesky through CHOLMOD: analyse once per pattern, factorise per matrix, solve.
// Only sparse_cholesky.cpp includes CHOLMOD.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "ddaslope/assembly/block_sparse_matrix.hpp"

namespace ddaslope::solver {

/// How the unknowns are ordered to limit the factor's fill.
enum class FillOrdering {
  MinimumDegree,     ///< AMD: cheap to compute, the default
  NestedDissection,  ///< CHOLMOD's NESDIS (METIS separators): less fill on large 2-D meshes
};

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Numeric factorisation; the symbolic analysis is redone only when the pattern changed.
  /// Returns false if the matrix is not positive definite.
  bool factorise(const assembly::BlockSparseMatrix& k);
  /// Solves K x = b with the last factorisation (and the low-rank changes applied since).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  /// One column c of a low-rank change K ± c cᵀ: up to 12 entries (rows distinct).
  struct Column {
    int count = 0;
    int rows[12];
    double values[12];
  };
  /// Changes the factor to that of K + Σ c cᵀ (add) or K − Σ c cᵀ, by CHOLMOD's update/downdate
  /// of a simplicial LDLᵀ copy (the supernodal factor stays for the next factorisation).
  /// Returns false if the result is not positive definite (the factor must then be redone).
  bool modify(const std::vector<Column>& columns, bool add);
  int symbolicAnalyses() const { return analyses_; }
  /// Entries of L (CHOLMOD's count for the last symbolic analysis; 0 before it).
  double factorEntries() const;
  /// The ordering of the next symbolic analysis (a change forces one at the next factorisation).
  void setOrdering(FillOrdering o);
  /// Solve with a simplicial LDLᵀ copy of each new factor (the form update/downdate needs
  /// anyway) instead of the supernodal factor: with Debian's reference BLAS its single
  /// right-hand-side solve is faster (docs/performance.md, "Measurements behind the solver's
  /// constants").
  void setSimplicialSolves(bool on) { simplicialSolves_ = on; }
  /// With simplicial solves: once the factor (as last modified) has served kSolvesBeforePanels
  /// solves (kSolvesBeforeRoundedPanels for rounded panels), substitute with its panels (solver/panel_factor.hpp) instead: from kPanelMinEntries
  /// entries rounded to single precision, a preconditioner within about 1e-7 of the factor that
  /// streams a third of the bytes; below, exact (double entries, the factor itself, without
  /// CHOLMOD's row index per entry and with vectorised kernels). Only for callers that check each
  /// solution against K (conjugate gradients) and announce each system solve with beginSolve().
  void setPanelSolves(bool on) { panelSolves_ = on; }
  /// A new system solve begins: it counts towards the factor's panels and fixes whether its
  /// substitutions use them (one preconditioner for a whole CG run). Without it, none do.
  void beginSolve();
  /// Whether this solve's substitutions use rounded panels (for the solver's tolerance logic:
  /// exact panels solve as the factor does).
  bool solvingWithPanels() const;
  /// The rest of this solve, and this factor, substitute in double precision: CG through the
  /// panels missed its budget (their rounding, about 6e-8 · κ(K), can, where K is stiff).
  void dropPanels();
  /// Substitutions made with the panels, and the bytes they hold (for the bench).
  long panelSubstitutions() const { return panelSubstitutions_; }
  double panelBytes() const;
  /// A factor's solves before its panels are built: a run whose factor changes at nearly every
  /// contact state change (sudden loading) keeps the double factor and seldom pays for a
  /// regrouping (about one and a half substitutions' worth) that it would use once.
  static constexpr int kSolvesBeforePanels = 8;
  /// The same for rounded panels (factors of kPanelMinEntries and more, read from memory): the
  /// regrouping costs about two of CHOLMOD's double-precision substitutions and each substitution
  /// through the panels saves four fifths of one, so they pay after two to three solves
  /// (build/ddaslope_substitution_bench times both). Exact panels keep kSolvesBeforePanels: under
  /// a sudden start smaller factors change after a few solves each, and regrouping them after two
  /// made that start slower (docs/performance.md, "Measurements behind the solver's constants").
  static constexpr int kSolvesBeforeRoundedPanels = 3;
  /// Smaller factors stay in the cache from one step to the next, where exact panels are solved
  /// as fast and need no conjugate-gradient iteration: rounded panels made the quiet walls with
  /// factors under a million entries slower (one CG iteration per step), and won from the
  /// smallest factor measured above it (docs/performance.md, "Measurements behind the solver's
  /// constants").
  static constexpr double kPanelMinEntries = 1e6;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int analyses_ = 0;
  bool simplicialSolves_ = false;
  bool panelSolves_ = false;
  long panelSubstitutions_ = 0;
};

}  // namespace ddaslope::solver
