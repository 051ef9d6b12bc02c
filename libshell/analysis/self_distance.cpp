#include "libshell/analysis/self_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <utility>
#include <vector>

#include "libshell/subdivision/element_lattice_sampling.hpp"

namespace growshell {
namespace {

/// Grid cell coordinates are packed into 21 bits each of one 64-bit key.
constexpr int kSampleCellKeyBits = 21;
constexpr std::int64_t kKeyRange = std::int64_t{1} << kSampleCellKeyBits;
/// Smallest cell size relative to the bounding-box diagonal: keeps every cell coordinate
/// below kKeyRange (1e6 < 2^21).
constexpr double kMinRelativeCell = 1e-6;

struct Samples {
  std::vector<Eigen::Vector3d> current, reference;
  std::vector<Eigen::Index> element;  ///< the element each sample was taken from
  double mean_spacing = 0.0;          ///< mean current distance of neighbouring samples (m)
};

struct Best {
  double squared = std::numeric_limits<double>::infinity();
  Eigen::Index a = -1, b = -1;
};

/// The distinct samples of all elements (see smallest_self_distance): a corner or edge
/// sample shared with other elements is kept only from the first element that has it, since
/// duplicates would multiply the pairs of the broad phase (by 9 for n = 2) without changing
/// the answer.
Samples sample_limit_surface(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x, int n,
                             const SelfDistanceOptions& options) {
  const Eigen::Index num_vertices = x.size() / 3;
  // The limit positions at every element's lattice points, current and reference.
  const ElementLatticeSampling& lattice = model.lattice_sampling(n);
  const Eigen::MatrixX3d current = lattice.state_positions(x);
  const Eigen::MatrixX3d& reference = lattice.reference_positions();
  Samples s;
  const auto per_element = static_cast<std::size_t>((n + 1) * (n + 2) / 2);
  s.current.reserve(per_element * static_cast<std::size_t>(model.num_elements()));
  s.reference.reserve(s.current.capacity());
  s.element.reserve(s.current.capacity());
  std::vector<char> vertex_taken(static_cast<std::size_t>(num_vertices), 0);
  std::unordered_set<std::uint64_t> edge_taken;
  const auto edge_key = [&](int p, int q) {
    return static_cast<std::uint64_t>(std::min(p, q)) * static_cast<std::uint64_t>(num_vertices) +
           static_cast<std::uint64_t>(std::max(p, q));
  };
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    // Corners: the face (a, b, c) at (v, w) = (0, 0), (1, 0), (0, 1) (loop_patch.hpp).
    const auto& f = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
    const int A = f[0], B = f[1], C = f[2];
    // An edge's inner samples belong to the first element that reaches it.
    const bool new_ab = edge_taken.insert(edge_key(A, B)).second;
    const bool new_ac = edge_taken.insert(edge_key(A, C)).second;
    const bool new_bc = edge_taken.insert(edge_key(B, C)).second;
    Eigen::Vector3d corner_a = Eigen::Vector3d::Zero();
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n - i; ++j) {
        bool keep = true;
        const int k = n - i - j;
        if ((i == 0 && j == 0) || (i == n) || (j == n)) {
          const int corner = (i == n) ? B : (j == n) ? C : A;
          keep = !vertex_taken[static_cast<std::size_t>(corner)];
          vertex_taken[static_cast<std::size_t>(corner)] = 1;
        } else if (j == 0) {
          keep = new_ab;
        } else if (i == 0) {
          keep = new_ac;
        } else if (k == 0) {
          keep = new_bc;
        }
        const bool spacing_corner = i == 0 && (j == 0 || j == n);
        if (!keep && !spacing_corner) continue;
        const Eigen::Vector3d p = current.row(lattice.row(e, i, j)).transpose();
        if (i == 0 && j == 0) corner_a = p;
        if (i == 0 && j == n) s.mean_spacing += (p - corner_a).norm();
        if (!keep) continue;
        const Eigen::Vector3d q = reference.row(lattice.row(e, i, j)).transpose();
        if ((q - options.core_center).norm() < options.core_radius) continue;
        s.current.push_back(p);
        s.reference.push_back(q);
        s.element.push_back(e);
      }
    }
  }
  if (model.num_elements() > 0) s.mean_spacing /= static_cast<double>(n) * static_cast<double>(model.num_elements());
  return s;
}

/// One broad-phase pass with cell size c: the best valid pair among all pairs in the same or
/// adjacent cells, which includes every pair closer than c.
Best grid_pass(const Samples& s, const Eigen::Vector3d& origin, double c, double exclusion_squared,
               Eigen::Index& pairs_checked) {
  const std::size_t n = s.current.size();
  std::vector<std::pair<std::uint64_t, Eigen::Index>> keyed(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t key = 0;
    for (int d = 0; d < 3; ++d) {
      const auto cell = static_cast<std::int64_t>(std::floor((s.current[k](d) - origin(d)) / c));
      key = (key << kSampleCellKeyBits) |
            static_cast<std::uint64_t>(std::clamp<std::int64_t>(cell, 0, kKeyRange - 1));
    }
    keyed[k] = {key, static_cast<Eigen::Index>(k)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint64_t> cell_key;
  std::vector<std::size_t> cell_begin;
  for (std::size_t k = 0; k < n; ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      cell_key.push_back(keyed[k].first);
      cell_begin.push_back(k);
    }
  }
  cell_begin.push_back(n);

  Best best;
  const auto consider = [&](Eigen::Index p, Eigen::Index q) {
    ++pairs_checked;
    const double squared = (s.current[static_cast<std::size_t>(p)] - s.current[static_cast<std::size_t>(q)]).squaredNorm();
    if (squared > best.squared) return;
    if ((s.reference[static_cast<std::size_t>(p)] - s.reference[static_cast<std::size_t>(q)]).squaredNorm() <
        exclusion_squared)
      return;
    const Eigen::Index a = std::min(p, q), b = std::max(p, q);
    if (squared < best.squared || a < best.a || (a == best.a && b < best.b)) best = {squared, a, b};
  };

  const std::uint64_t mask = static_cast<std::uint64_t>(kKeyRange - 1);
  for (std::size_t cell = 0; cell + 1 < cell_begin.size(); ++cell) {
    const std::size_t begin = cell_begin[cell], end = cell_begin[cell + 1];
    for (std::size_t p = begin; p < end; ++p)
      for (std::size_t q = p + 1; q < end; ++q) consider(keyed[p].second, keyed[q].second);
    const std::int64_t ix =
        static_cast<std::int64_t>((cell_key[cell] >> (2 * kSampleCellKeyBits)) & mask);
    const std::int64_t iy =
        static_cast<std::int64_t>((cell_key[cell] >> kSampleCellKeyBits) & mask);
    const std::int64_t iz = static_cast<std::int64_t>(cell_key[cell] & mask);
    // Half of the 26 neighbours (the lexicographically larger offsets): each unordered pair
    // of cells is visited once.
    for (int dx = 0; dx <= 1; ++dx) {
      for (int dy = (dx == 0 ? 0 : -1); dy <= 1; ++dy) {
        for (int dz = (dx == 0 && dy == 0 ? 1 : -1); dz <= 1; ++dz) {
          const std::int64_t jx = ix + dx, jy = iy + dy, jz = iz + dz;
          if (jx >= kKeyRange || jy < 0 || jy >= kKeyRange || jz < 0 || jz >= kKeyRange) continue;
          const std::uint64_t key = (static_cast<std::uint64_t>(jx) << (2 * kSampleCellKeyBits)) |
                                    (static_cast<std::uint64_t>(jy) << kSampleCellKeyBits) |
                                    static_cast<std::uint64_t>(jz);
          const auto it = std::lower_bound(cell_key.begin(), cell_key.end(), key);
          if (it == cell_key.end() || *it != key) continue;
          const auto other = static_cast<std::size_t>(it - cell_key.begin());
          for (std::size_t p = begin; p < end; ++p)
            for (std::size_t q = cell_begin[other]; q < cell_begin[other + 1]; ++q)
              consider(keyed[p].second, keyed[q].second);
        }
      }
    }
  }
  return best;
}

}  // namespace

SelfDistance smallest_self_distance(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const SelfDistanceOptions& options) {
  if (!(options.exclusion_radius > 0.0)) {
    std::ostringstream msg;
    msg << "SelfDistanceOptions.exclusion_radius must be > 0 (metres), got " << options.exclusion_radius;
    throw std::invalid_argument(msg.str());
  }
  if (options.samples_per_edge < 1) {
    std::ostringstream msg;
    msg << "SelfDistanceOptions.samples_per_edge must be >= 1, got " << options.samples_per_edge;
    throw std::invalid_argument(msg.str());
  }
  if (!(options.core_radius >= 0.0) || !std::isfinite(options.core_radius)) {
    std::ostringstream msg;
    msg << "SelfDistanceOptions.core_radius must be finite and >= 0 (metres), got "
        << options.core_radius;
    throw std::invalid_argument(msg.str());
  }
  if (x.size() != model.dimension()) {
    std::ostringstream msg;
    msg << "smallest_self_distance: x has " << x.size() << " entries, the model has dimension "
        << model.dimension();
    throw std::invalid_argument(msg.str());
  }

  for (Eigen::Index k = 0; k < x.size(); ++k) {
    if (!std::isfinite(x(k))) {
      std::ostringstream msg;
      msg << "smallest_self_distance: x(" << k << ") (vertex " << k / 3 << ", coordinate " << k % 3
          << ") is not finite";
      throw std::invalid_argument(msg.str());
    }
  }

  const int n = options.samples_per_edge;
  const Samples s = sample_limit_surface(model, x, n, options);
  SelfDistance result;
  if (s.current.size() < 2) return result;

  Eigen::Vector3d lo = s.current.front(), hi = s.current.front();
  for (const auto& p : s.current) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  const double spacing = s.mean_spacing;

  const double exclusion_squared = options.exclusion_radius * options.exclusion_radius;
  // All samples on one point (diagonal 0): one pass with any cell size puts them in one cell.
  double c = diagonal > 0.0 ? std::max(spacing, kMinRelativeCell * diagonal) : 1.0;
  Best best;
  for (;;) {
    best = grid_pass(s, lo, c, exclusion_squared, result.pairs_checked);
    // Below c the pass saw every pair closer than c, so it saw the true minimum; at c >=
    // the diagonal every pair shares or neighbours a cell.
    if (best.squared < c * c || c >= diagonal || diagonal == 0.0) break;
    c = std::isfinite(best.squared) ? std::sqrt(best.squared) * (1.0 + 1e-9) : 2.0 * c;
  }

  if (best.a < 0) return result;
  const auto a = static_cast<std::size_t>(best.a), b = static_cast<std::size_t>(best.b);
  result.distance = std::sqrt(best.squared);
  result.point_a = s.current[a];
  result.point_b = s.current[b];
  result.reference_a = s.reference[a];
  result.reference_b = s.reference[b];
  result.element_a = s.element[a];
  result.element_b = s.element[b];
  return result;
}

}  // namespace growshell
