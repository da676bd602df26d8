#pragma once
/// @file
/// A scene of the paper's Sec.\ 5: a row kernel, a linear part, an initial state and a parameter
/// box, nothing else. Everything derived (gradients, Jacobians, Hessians, the shift, time
/// integration) comes from packages/core and packages/timeint.
#include <Teuchos_ParameterList.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gphr/core/HamiltonianSystem.hpp"

namespace gphr {

/// Where a parameter enters a scene (flags, combined with |). A reduced-model query rebuilds only
/// what its parameters touch: the row kernel (n-independent, rebuilt exactly per query), the
/// linear part L, f (hence L_r, f_r and c) and the initial state (hence the shift's reference
/// state y0, f_r = A^T (f + L y0), c = H(y0) and the reference rows of the sample mesh).
enum ParameterEntry : unsigned { EntersRowKernel = 1u, EntersLinearPart = 2u, EntersInitialState = 4u };

/// The parameter box of a scene: names, [lower, upper] per parameter, and where each enters.
struct ParameterBox {
  std::vector<std::string> names;  ///< Parameter names (the keys of the `parameters` section).
  std::vector<std::pair<double, double>> bounds;  ///< [lower, upper] per parameter.
  std::vector<unsigned> enters;  ///< per parameter, ParameterEntry flags
  /// Throws InputError naming the parameter, its value and the box when mu lies outside.
  void check(const std::vector<double>& mu) const;
};

/// The grid a scene's state lives on, for the field pictures and the ParaView output: a uniform
/// grid of points, the first direction fastest (point index i = i_x + points[0] (i_y + ...)). The
/// state y = (q, p) holds one block of numPoints() values per component, in `components` order.
struct SceneGrid {
  std::vector<GO> points;          ///< points per direction, x first (1 to 3 directions)
  std::vector<double> origin;      ///< coordinates of point 0, per direction
  std::vector<double> spacing;     ///< distance between neighbouring points, per direction
  std::vector<std::string> components;  ///< physical names of the state's blocks, in state order
  /// The components are the real and imaginary parts of one complex field (NLS' u = q + i p):
  /// pictures show its modulus, the quantity a reader of the paper knows.
  bool complexField = false;
  GO numPoints() const;  ///< the product of `points`
  /// Throws InputError unless the grid is well formed and numPoints() * components equals fullDim.
  void check(GO fullDim, const std::string& scene) const;
};

/// A scene instantiated at one parameter value.
struct SceneInstance {
  RCP<HamiltonianSystem> system;  ///< shifted when asked (then y0 = 0 and system->reference() holds it)
  RCP<Vector> y0;                 ///< initial state of `system`
  RCP<const Vector> physicalInitialState;  ///< the unshifted initial state
};

/// A scene of the paper's Sec.\ 5: row kernel, linear part, initial state, parameter box (the file's description).
class Scene {
 public:
  virtual ~Scene() = default;
  virtual std::string name() const = 0;  ///< The scene's name in the config (nls1d, swe2d, ...).
  virtual const ParameterBox& parameterBox() const = 0;  ///< The scene's parameter box.
  /// Unshifted Hamiltonian system and initial state at parameter mu (not checked against the box:
  /// tests use e.g.\ eps = 0 for the linear NLS).
  virtual std::pair<RCP<HamiltonianSystem>, RCP<Vector>> build(const RCP<const Comm>& comm,
                                                              const std::vector<double>& mu) const = 0;
  /// The row kernel alone at mu (no maps, stencils or weights: nothing of size n or d), equal to
  /// the kernel of build(comm, mu)'s nonlinear term: what an online model loaded from a
  /// reduced-model file evaluates.
  virtual RCP<const RowEvaluator> rowKernel(const std::vector<double>& mu) const = 0;
  /// The grid of the state, for pictures and ParaView; a scene without one (the default) gets
  /// neither, with a message saying so.
  virtual std::optional<SceneGrid> grid() const { return std::nullopt; }
  /// The system and initial state at mu on the layout of `like`, a system this scene built (at any
  /// parameter, shifted or not) on the communicator wanted: the phase space, the graph of L and the
  /// nonlinear term's layout (stencils, weights v, J_G's graph, its import) are shared and only the
  /// values are computed. Equal to build(like's communicator, mu). The default builds afresh; the
  /// scenes here share the layout (a model file's interpolation instantiates one system per node:
  /// the instance was about half of a SWE node's time, perf of a SWE 256^2 build).
  virtual std::pair<RCP<HamiltonianSystem>, RCP<Vector>> rebuild(const HamiltonianSystem& like,
                                                                const std::vector<double>& mu) const;
  /// build() then, if shift is set, the shifted system of paper eq:shiftH with y0 = 0.
  SceneInstance instantiate(const RCP<const Comm>& comm, const std::vector<double>& mu, bool shift) const;
  /// rebuild() then, if shift is set, the shifted system: instantiate() on the layout of `like`.
  SceneInstance instantiate(const HamiltonianSystem& like, const std::vector<double>& mu, bool shift) const;
};

/// The NLS scene (paper eq:schrodinger): u = q + i p on [-L, L), L = pi/0.11, n points,
/// H = 1/2 q^T(-Dxx)q + 1/2 p^T(-Dxx)p - eps/4 sum_i (q_i^2 + p_i^2)^2  (not scaled by dx; doc/scenes.md).
class Nls1d final : public Scene {
 public:
  /// NLS with n grid points on [-halfLength, halfLength). pulseParameters: the scene nls1d-pulse,
  /// whose box adds the initial pulse's amplitude a and velocity c, u0 = a sqrt(2) sech(x) e^{i c x}
  /// (the paper's a = 1, c = 1/2), to eps: three parameters, two of them in y0 only.
  explicit Nls1d(GO n, double halfLength = 3.14159265358979323846 / 0.11, bool pulseParameters = false);
  std::string name() const override { return pulse_ ? "nls1d-pulse" : "nls1d"; }
  const ParameterBox& parameterBox() const override { return box_; }
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> build(const RCP<const Comm>& comm,
                                                      const std::vector<double>& mu) const override;
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> rebuild(const HamiltonianSystem& like,
                                                        const std::vector<double>& mu) const override;
  RCP<const RowEvaluator> rowKernel(const std::vector<double>& mu) const override;
  std::optional<SceneGrid> grid() const override;  ///< the periodic grid of x (and y)
  GO n() const { return n_; }  ///< n, the number of grid points.

 private:
  /// build() (like = nullptr) and rebuild() (on like's layout): one loop over the rows for both.
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> assemble(const HamiltonianSystem* like, const RCP<const Comm>& comm,
                                                         const std::vector<double>& mu) const;
  GO n_;
  double L_;
  bool pulse_ = false;  ///< nls1d-pulse: amplitude and velocity are parameters too
  ParameterBox box_;
};

/// The 2D shallow-water scene (paper eq:2Dsw_eq_final, potential form): y = (chi, Phi) on
/// [-2, 2)^2 with nx points per direction, H = gamma/2 sum_i chi_i^2 + gamma/2 sum_i chi_i
/// [(D1 Phi)_i^2 + (D2 Phi)_i^2] (not scaled by the cell area; doc/scenes.md).
class Swe2d final : public Scene {
 public:
  explicit Swe2d(GO nx, double halfLength = 2.0);  ///< SWE with nx x nx grid points on [-halfLength, halfLength)^2.
  std::string name() const override { return "swe2d"; }
  const ParameterBox& parameterBox() const override { return box_; }
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> build(const RCP<const Comm>& comm,
                                                      const std::vector<double>& mu) const override;
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> rebuild(const HamiltonianSystem& like,
                                                        const std::vector<double>& mu) const override;
  RCP<const RowEvaluator> rowKernel(const std::vector<double>& mu) const override;
  std::optional<SceneGrid> grid() const override;  ///< the periodic grid of x (and y)
  GO nx() const { return nx_; }  ///< nx, grid points per direction.

 private:
  /// build() (like = nullptr) and rebuild() (on like's layout): one loop over the rows for both.
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> assemble(const HamiltonianSystem* like, const RCP<const Comm>& comm,
                                                         const std::vector<double>& mu) const;
  GO nx_;
  double L_;
  ParameterBox box_;
};

/// NLS discrete mass sum_i (q_i^2 + p_i^2) of a physical (unshifted) state: a quadratic invariant
/// that IMR conserves exactly.
double nlsMass(const Vector& y);

}  // namespace gphr
