#pragma once
// Symmetry planes for the correspondence model: bonds from the points near a plane to the mirror images of
// their neighbours (a rigid wall with `contact: symmetry`, contact/rigid_wall.hpp).
//
// Why: a frictionless rigid anvil and the mid-plane of two identical bodies meeting head on load a body in
// the same way (by symmetry the mid-plane carries no shear and does not move), but a penalty wall pushes
// only the layer of points that touches it, while a body's own surface force is spread over the horizon: the
// layers near the wall then alternate, a zero-energy mode of the correspondence model that the contact drives
// (examples/taylor_impact/README.md, "The face layers"). Bonded to their mirror images, the near-plane points
// have whole families and are loaded as the interior is.
//
// The plane through p with unit normal n reflects by M = I − 2 n⊗n: the mirror image j' of point j is at
// X_j' = X_j − 2((X_j − p)·n) n, its displacement is M u_j, its velocity M v_j, and its state is j's
// reflected: F_j' = M F_j M, Ḟ_j' = M Ḟ_j M, P_j' K_j'⁻¹ = M P_j K_j⁻¹ M. Point i bonds to j' when
// |X_j' − X_i| is within the horizon of the pair (the neighbour search's test, with partial volumes). Since
// |X_j − X_i| ≤ |X_j' − X_i| for points on the same side, every such j is i itself or in i's family, so the
// mirror partners are found among those (a bond cut by a pre-crack is not mirrored). The bond i → j' enters
// K, F, Ḟ and the force gather of i exactly like a bond to a real point, with the weight ω_i(|ξ'|) and, for
// the partner's end, ω_j(|ξ'|) (j' → i is the mirror image of j → i').
//
// The bodies are welded to their images, so the bonds hold tension too: they are released, all at once and
// for good, the first step at which the bodies touching the plane move away from it (their momentum along n
// is positive) and the total normal force of the mirror bonds on them is tensile: the body leaves the anvil.
// The force alone would not do: right after an impact the near-plane layers ring in phase over the whole
// face, and the total force is tensile for a step or two while the body still moves into the plane. Both
// sums are exact over all ranks (reproducible_sum), so the release is the same step for any rank count. The
// wall's penalty contact stays for any later contact. Distributed, a mirror partner (i itself or in i's
// family) is owned or a ghost, and its state is what the ghost exchange already brings.
// What the mirror bonds exert on the bodies is the force of the plane on them (the wall's force in the
// history is its opposite). A fixed plane does no work on the symmetric pair, so the energy balance has no
// term for it.
#include <cstdint>
#include <vector>

#include "peridot/core/vec3.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/state/fields.hpp"

namespace peridot::correspondence {

struct MirrorPlane {
  Vec3 point;   ///< p (m)
  Vec3 normal;  ///< n, unit, toward the bodies
  std::size_t wall = 0;  ///< index of its wall among the problem's rigid walls
  bool active = true;     ///< its bonds are in the sums (until released)
  std::vector<std::uint8_t> block_touches;  ///< per block: some point of it has mirror bonds across this plane
};

/// CSR of the mirror bonds of every point (empty ranges for the points far from every plane).
struct MirrorBonds {
  std::vector<MirrorPlane> planes;
  std::vector<std::uint64_t> offsets;    ///< size N + 1 (empty: no symmetry plane)
  std::vector<std::uint32_t> source;     ///< j of the bond i → j'
  std::vector<double> weight;            ///< ω_i(|ξ'|) times the partial-volume factor
  std::vector<double> partner_weight;    ///< ω_j(|ξ'|) times the partial-volume factor (the bond j' → i)
  std::vector<std::uint8_t> plane_of;    ///< per point: its plane (meaningful where it has mirror bonds)
  /// Some plane is active. Distributed, a plane stays active on a rank without any of its bonds, so that every
  /// rank takes part in the release decision.
  bool active = false;

  bool empty() const { return source.empty(); }  ///< no mirror bond on this rank
};

/// x − 2((x − p)·n) n
inline Vec3 reflect_point(const MirrorPlane& plane, Vec3 x) {
  return x - (2 * dot(x - plane.point, plane.normal)) * plane.normal;
}
/// M a = a − 2(a·n) n
inline void reflect_vector(const Vec3& n, const double* a, double* out) {
  const double s = 2 * (a[0] * n.x + a[1] * n.y + a[2] * n.z);
  for (int d = 0; d < 3; ++d) out[d] = a[d] - s * n[d];
}
/// M A M for a row-major 3×3 A: (M A M)_rc = A_rc − 2 n_r (nᵀA)_c − 2 (A n)_r n_c + 4 n_r n_c (nᵀA n)
inline void reflect_tensor(const Vec3& n, const double* A, double* out) {
  double An[3], nA[3], nAn = 0;
  for (int r = 0; r < 3; ++r) {
    An[r] = A[3 * r] * n.x + A[3 * r + 1] * n.y + A[3 * r + 2] * n.z;
    nA[r] = n.x * A[r] + n.y * A[3 + r] + n.z * A[6 + r];
  }
  for (int r = 0; r < 3; ++r) nAn += n[r] * An[r];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[3 * r + c] = A[3 * r + c] - 2 * n[r] * nA[c] - 2 * An[r] * n[c] + 4 * n[r] * n[c] * nAn;
}

/// Reference offset ξ = X_j − X_i, relative displacement u_j − u_i and relative velocity v_j − v_i of the
/// bond i → j, from point-major x, u, v (3 per point): what the kinematics and the force gather read of a bond.
inline void bond_offsets(const double* x, const double* u, const double* v, std::size_t i, std::size_t j,
                         double* xi, double* du, double* dv) {
  for (int d = 0; d < 3; ++d) {
    xi[d] = x[3 * j + d] - x[3 * i + d];
    du[d] = u[3 * j + d] - u[3 * i + d];
    dv[d] = v[3 * j + d] - v[3 * i + d];
  }
}
/// The same for the bond i → j′ to the mirror image of j across `plane`: X_j′ − X_i, M u_j − u_i, M v_j − v_i.
inline void mirror_bond_offsets(const MirrorPlane& plane, const double* x, const double* u, const double* v,
                                std::size_t i, std::size_t j, double* xi, double* du, double* dv) {
  const Vec3 image = reflect_point(plane, Vec3{x[3 * j], x[3 * j + 1], x[3 * j + 2]});
  double uj[3], vj[3];
  reflect_vector(plane.normal, u + 3 * j, uj);
  reflect_vector(plane.normal, v + 3 * j, vj);
  for (int d = 0; d < 3; ++d) {
    xi[d] = image[d] - x[3 * i + d];
    du[d] = uj[d] - u[3 * i + d];
    dv[d] = vj[d] - v[3 * i + d];
  }
}

/// What the mirror bonds need of the points and their blocks.
struct MirrorBondOptions {
  std::vector<double> horizon_of_block;       ///< δ per block (m); a pair bonds within max(δ_i, δ_j)
  std::vector<InfluenceKind> influence_of_block;
  std::vector<std::uint8_t> block_is_mirrored;  ///< per block: 1 for a correspondence block
  double partial_volume_radius = 0;           ///< as NeighborhoodOptions
  bool bond_beyond_horizon = false;
};

/// The mirror bonds of every point of a mirrored block in [0, owned) across `planes`, found among the
/// point itself and its family in `bonds`; active when this rank has any (CorrespondenceBlocks makes every
/// rank's active). PERIDOT_REQUIRE fails for a point
/// with mirror bonds across two planes (the caller refuses such a deck first).
MirrorBonds build_mirror_bonds(const Discretization& disc, const BondList& bonds, std::size_t owned,
                               const std::vector<MirrorPlane>& planes, const MirrorBondOptions& options);

}  // namespace peridot::correspondence
