#include "libshell/analysis/self_intersection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "libshell/analysis/self_distance.hpp"
#include "libshell/subdivision/element_lattice_sampling.hpp"

namespace growshell {
namespace {

/// Grid cell coordinates are packed into 21 bits each of one 64-bit key.
constexpr int kCellKeyBits = 21;
constexpr std::int64_t kCellKeyRange = std::int64_t{1} << kCellKeyBits;
/// Smallest cell size relative to the bounding-box diagonal: keeps every cell coordinate
/// below kCellKeyRange (1e6 < 2^21).
constexpr double kMinRelativeCellSize = 1e-6;
/// Cell entries allowed per triangle before the cell size is doubled: a few huge (stretched)
/// triangles must not fill millions of cells.
constexpr std::size_t kMaxCellsPerTriangle = 64;

using Triangle = std::array<Eigen::Index, 3>;

/// The conforming sub-triangulation of the limit surface (see find_self_intersection).
struct SampledSurface {
  std::vector<Eigen::Vector3d> current, reference;
  std::vector<Triangle> triangles;           ///< sample indices, counter-clockwise in (v, w)
  std::vector<Eigen::Index> element;         ///< element of each triangle
};

SampledSurface sample_surface(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x, int n) {
  const Eigen::Index num_vertices = x.size() / 3;
  // The limit positions at every element's lattice points, current and reference.
  const ElementLatticeSampling& lattice = model.lattice_sampling(n);
  const Eigen::MatrixX3d current = lattice.state_positions(x);
  const Eigen::MatrixX3d& reference = lattice.reference_positions();

  SampledSurface s;
  std::vector<char> evaluated;
  std::vector<Eigen::Index> vertex_sample(static_cast<std::size_t>(num_vertices), -1);
  // Edge (p < q) -> index of its first inner sample; the n - 1 inner samples follow in the
  // order from p to q.
  std::unordered_map<std::uint64_t, Eigen::Index> edge_first_sample;
  const auto reserve_samples = [&](std::size_t count) {
    const auto first = static_cast<Eigen::Index>(s.current.size());
    s.current.resize(s.current.size() + count, Eigen::Vector3d::Zero());
    s.reference.resize(s.current.size(), Eigen::Vector3d::Zero());
    evaluated.resize(s.current.size(), 0);
    return first;
  };

  std::vector<Eigen::Index> local(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    // Corners: the face (a, b, c) at (v, w) = (0, 0), (1, 0), (0, 1) (loop_patch.hpp).
    const auto& f = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
    const int A = f[0], B = f[1], C = f[2];
    const auto vertex = [&](int v) {
      Eigen::Index& index = vertex_sample[static_cast<std::size_t>(v)];
      if (index < 0) index = reserve_samples(1);
      return index;
    };
    const auto edge = [&](int p, int q, int steps_from_p) {
      const int lo = std::min(p, q), hi = std::max(p, q);
      const std::uint64_t key = static_cast<std::uint64_t>(lo) * static_cast<std::uint64_t>(num_vertices) +
                                static_cast<std::uint64_t>(hi);
      auto it = edge_first_sample.find(key);
      if (it == edge_first_sample.end())
        it = edge_first_sample.emplace(key, reserve_samples(static_cast<std::size_t>(n - 1))).first;
      const int steps_from_lo = (p == lo) ? steps_from_p : n - steps_from_p;
      return it->second + steps_from_lo - 1;
    };
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n - i; ++j) {
        Eigen::Index index;
        if (i == 0 && j == 0) index = vertex(A);
        else if (i == n) index = vertex(B);
        else if (j == n) index = vertex(C);
        else if (j == 0) index = edge(A, B, i);
        else if (i == 0) index = edge(A, C, j);
        else if (i + j == n) index = edge(B, C, j);  // from B = (n, 0) towards C = (0, n)
        else index = reserve_samples(1);
        const auto k = static_cast<std::size_t>(index);
        if (!evaluated[k]) {
          s.current[k] = current.row(lattice.row(e, i, j)).transpose();
          s.reference[k] = reference.row(lattice.row(e, i, j)).transpose();
          evaluated[k] = 1;
        }
        local[static_cast<std::size_t>(i * (n + 1) + j)] = index;
      }
    }
    const auto at = [&](int i, int j) { return local[static_cast<std::size_t>(i * (n + 1) + j)]; };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n - i; ++j) {
        s.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        s.element.push_back(e);
        if (i + j < n - 1) {
          s.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
          s.element.push_back(e);
        }
      }
    }
  }
  return s;
}

/// Where segment pq meets triangle abc with (unnormalised, non-zero) normal nrm, if it
/// crosses or touches it; nothing if the segment lies in the triangle's plane (the other
/// edges, or the coplanar test, decide then).
std::optional<Eigen::Vector3d> segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                      const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                      const Eigen::Vector3d& c, const Eigen::Vector3d& nrm) {
  const double dp = nrm.dot(p - a), dq = nrm.dot(q - a);
  if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || (dp == 0.0 && dq == 0.0)) return std::nullopt;
  // t in [0, 1] since dp, dq have opposite signs (or one is zero): the point stays on the
  // segment however ill-conditioned t is for a nearly parallel segment.
  const double t = dp / (dp - dq);
  const Eigen::Vector3d point = p + t * (q - p);
  // Inside (boundary included) iff on the inner side of all three edges, seen along nrm.
  if (nrm.dot((b - a).cross(point - a)) < 0.0) return std::nullopt;
  if (nrm.dot((c - b).cross(point - b)) < 0.0) return std::nullopt;
  if (nrm.dot((a - c).cross(point - c)) < 0.0) return std::nullopt;
  return point;
}

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// Whether 2-D point p lies in triangle t (either orientation, boundary included).
bool inside2(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& p) {
  const double d0 = cross2(t[1] - t[0], p - t[0]);
  const double d1 = cross2(t[2] - t[1], p - t[1]);
  const double d2 = cross2(t[0] - t[2], p - t[2]);
  return (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0);
}

/// Overlap of two triangles in one plane (normal nrm): a vertex of one inside the other or
/// two crossing edges. Collinear overlapping edges always put a vertex on the other's edge,
/// which the inside test (boundary included) finds.
std::optional<Eigen::Vector3d> coplanar_overlap(const std::array<Eigen::Vector3d, 3>& t1,
                                                const std::array<Eigen::Vector3d, 3>& t2,
                                                const Eigen::Vector3d& nrm) {
  // Project along the dominant normal component: the projection keeps the 2-D overlap.
  int drop = 0;
  nrm.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  std::array<Eigen::Vector2d, 3> p1, p2;
  for (int k = 0; k < 3; ++k) {
    p1[static_cast<std::size_t>(k)] = {t1[static_cast<std::size_t>(k)](u), t1[static_cast<std::size_t>(k)](v)};
    p2[static_cast<std::size_t>(k)] = {t2[static_cast<std::size_t>(k)](u), t2[static_cast<std::size_t>(k)](v)};
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (inside2(p2, p1[k])) return t1[k];
    if (inside2(p1, p2[k])) return t2[k];
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t k1 = (k + 1) % 3;
    for (std::size_t m = 0; m < 3; ++m) {
      const std::size_t m1 = (m + 1) % 3;
      const double s0 = cross2(p1[k1] - p1[k], p2[m] - p1[k]), s1 = cross2(p1[k1] - p1[k], p2[m1] - p1[k]);
      const double r0 = cross2(p2[m1] - p2[m], p1[k] - p2[m]), r1 = cross2(p2[m1] - p2[m], p1[k1] - p2[m]);
      if ((s0 > 0.0 && s1 > 0.0) || (s0 < 0.0 && s1 < 0.0) || (s0 == 0.0 && s1 == 0.0)) continue;
      if ((r0 > 0.0 && r1 > 0.0) || (r0 < 0.0 && r1 < 0.0) || (r0 == 0.0 && r1 == 0.0)) continue;
      const double t = r0 / (r0 - r1);
      return Eigen::Vector3d(t1[k] + t * (t1[k1] - t1[k]));
    }
  }
  return std::nullopt;
}

/// A point common to triangles t1 and t2, if they intersect (see find_self_intersection).
std::optional<Eigen::Vector3d> triangles_intersect(const std::array<Eigen::Vector3d, 3>& t1,
                                                   const std::array<Eigen::Vector3d, 3>& t2) {
  const Eigen::Vector3d n1 = (t1[1] - t1[0]).cross(t1[2] - t1[0]);
  const Eigen::Vector3d n2 = (t2[1] - t2[0]).cross(t2[2] - t2[0]);
  if (n1.squaredNorm() == 0.0 || n2.squaredNorm() == 0.0) return std::nullopt;
  // Early out (Moeller 1997): all vertices of one strictly on one side of the other's plane.
  std::array<double, 3> d1{}, d2{};
  for (std::size_t k = 0; k < 3; ++k) {
    d1[k] = n2.dot(t1[k] - t2[0]);
    d2[k] = n1.dot(t2[k] - t1[0]);
  }
  const auto one_side = [](const std::array<double, 3>& d) {
    return (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0);
  };
  if (one_side(d1) || one_side(d2)) return std::nullopt;
  if (d1[0] == 0.0 && d1[1] == 0.0 && d1[2] == 0.0) return coplanar_overlap(t1, t2, n2);
  if (d2[0] == 0.0 && d2[1] == 0.0 && d2[2] == 0.0) return coplanar_overlap(t1, t2, n1);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t k1 = (k + 1) % 3;
    if (auto hit = segment_meets_triangle(t1[k], t1[k1], t2[0], t2[1], t2[2], n2)) return hit;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t k1 = (k + 1) % 3;
    if (auto hit = segment_meets_triangle(t2[k], t2[k1], t1[0], t1[1], t1[2], n1)) return hit;
  }
  return std::nullopt;
}

void validate(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
              const SelfIntersectionOptions& options, const char* caller) {
  std::ostringstream msg;
  if (!(options.exclusion_radius > 0.0)) {
    msg << "SelfIntersectionOptions.exclusion_radius must be > 0 (metres), got " << options.exclusion_radius;
  } else if (options.samples_per_edge < 1) {
    msg << "SelfIntersectionOptions.samples_per_edge must be >= 1, got " << options.samples_per_edge;
  } else if (!(options.core_radius >= 0.0) || !std::isfinite(options.core_radius)) {
    msg << "SelfIntersectionOptions.core_radius must be finite and >= 0 (metres), got " << options.core_radius;
  } else if (!options.core_center.allFinite()) {
    msg << "SelfIntersectionOptions.core_center must be finite, got (" << options.core_center.transpose() << ")";
  } else if (x.size() != model.dimension()) {
    msg << caller << ": x has " << x.size() << " entries, the model has dimension " << model.dimension();
  } else {
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      if (!std::isfinite(x(k))) {
        msg << caller << ": x(" << k << ") (vertex " << k / 3 << ", coordinate " << k % 3 << ") is not finite";
        break;
      }
    }
  }
  if (!msg.str().empty()) throw std::invalid_argument(msg.str());
}

SelfIntersection find_self_intersection_unchecked(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  const SelfIntersectionOptions& options) {
  SelfIntersection result;
  const SampledSurface s = sample_surface(model, x, options.samples_per_edge);

  // Triangles outside the core, with their bounding boxes.
  std::vector<Eigen::Index> kept;
  std::vector<Eigen::Vector3d> box_lo, box_hi;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    bool in_core = false;
    for (const Eigen::Index k : s.triangles[t])
      in_core = in_core || (s.reference[static_cast<std::size_t>(k)] - options.core_center).norm() < options.core_radius;
    if (in_core) continue;
    kept.push_back(static_cast<Eigen::Index>(t));
    const auto& tri = s.triangles[t];
    const Eigen::Vector3d& a = s.current[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d& b = s.current[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3d& c = s.current[static_cast<std::size_t>(tri[2])];
    box_lo.push_back(a.cwiseMin(b).cwiseMin(c));
    box_hi.push_back(a.cwiseMax(b).cwiseMax(c));
  }
  if (kept.size() < 2) return result;

  Eigen::Vector3d lo = box_lo.front(), hi = box_hi.front();
  double mean_size = 0.0;
  for (std::size_t t = 0; t < kept.size(); ++t) {
    lo = lo.cwiseMin(box_lo[t]);
    hi = hi.cwiseMax(box_hi[t]);
    mean_size += (box_hi[t] - box_lo[t]).maxCoeff();
  }
  mean_size /= static_cast<double>(kept.size());
  const double diagonal = (hi - lo).norm();
  double c = diagonal > 0.0 ? std::max(mean_size, kMinRelativeCellSize * diagonal) : 1.0;
  const auto cell_of = [&](const Eigen::Vector3d& p) {
    std::array<std::int64_t, 3> cell{};
    for (int d = 0; d < 3; ++d)
      cell[static_cast<std::size_t>(d)] = std::clamp<std::int64_t>(
          static_cast<std::int64_t>(std::floor((p(d) - lo(d)) / c)), 0, kCellKeyRange - 1);
    return cell;
  };
  const auto key_of = [](const std::array<std::int64_t, 3>& cell) {
    return (static_cast<std::uint64_t>(cell[0]) << (2 * kCellKeyBits)) |
           (static_cast<std::uint64_t>(cell[1]) << kCellKeyBits) |
           static_cast<std::uint64_t>(cell[2]);
  };
  const auto cells_spanned = [&](std::size_t t) {
    const auto a = cell_of(box_lo[t]), b = cell_of(box_hi[t]);
    // In double: up to (2^21)^3 cells per triangle.
    return static_cast<double>(b[0] - a[0] + 1) * static_cast<double>(b[1] - a[1] + 1) *
           static_cast<double>(b[2] - a[2] + 1);
  };
  for (;;) {
    double total = 0.0;
    for (std::size_t t = 0; t < kept.size(); ++t) total += cells_spanned(t);
    if (total <= static_cast<double>(kMaxCellsPerTriangle * kept.size()) || c >= diagonal) break;
    c *= 2.0;
  }

  // (cell key, position in kept), sorted: the triangles of each cell are contiguous.
  std::vector<std::pair<std::uint64_t, std::size_t>> entries;
  for (std::size_t t = 0; t < kept.size(); ++t) {
    const auto a = cell_of(box_lo[t]), b = cell_of(box_hi[t]);
    for (std::int64_t ix = a[0]; ix <= b[0]; ++ix)
      for (std::int64_t iy = a[1]; iy <= b[1]; ++iy)
        for (std::int64_t iz = a[2]; iz <= b[2]; ++iz) entries.emplace_back(key_of({ix, iy, iz}), t);
  }
  std::sort(entries.begin(), entries.end());

  const double exclusion_squared = options.exclusion_radius * options.exclusion_radius;
  const auto admissible = [&](const Triangle& p, const Triangle& q) {
    for (const Eigen::Index a : p)
      for (const Eigen::Index b : q)
        if ((s.reference[static_cast<std::size_t>(a)] - s.reference[static_cast<std::size_t>(b)]).squaredNorm() <
            exclusion_squared)
          return false;
    return true;
  };
  const auto corners = [&](const Triangle& tri) {
    return std::array<Eigen::Vector3d, 3>{s.current[static_cast<std::size_t>(tri[0])],
                                          s.current[static_cast<std::size_t>(tri[1])],
                                          s.current[static_cast<std::size_t>(tri[2])]};
  };

  std::pair<Eigen::Index, Eigen::Index> best{-1, -1};
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    const std::uint64_t cell_key = entries[begin].first;
    for (std::size_t p = begin; p < end; ++p) {
      for (std::size_t q = p + 1; q < end; ++q) {
        const std::size_t tp = entries[p].second, tq = entries[q].second;
        if ((box_lo[tp].array() > box_hi[tq].array()).any() || (box_lo[tq].array() > box_hi[tp].array()).any())
          continue;
        // Test each overlapping pair only in the cell holding the low corner of the
        // intersection of the boxes (a cell both triangles were entered in).
        if (key_of(cell_of(box_lo[tp].cwiseMax(box_lo[tq]))) != cell_key) continue;
        const Eigen::Index ta = std::min(kept[tp], kept[tq]), tb = std::max(kept[tp], kept[tq]);
        const auto& triangle_a = s.triangles[static_cast<std::size_t>(ta)];
        const auto& triangle_b = s.triangles[static_cast<std::size_t>(tb)];
        if (!admissible(triangle_a, triangle_b)) continue;
        ++result.triangle_pairs_tested;
        const auto hit = triangles_intersect(corners(triangle_a), corners(triangle_b));
        if (!hit) continue;
        if (best.first < 0 || std::make_pair(ta, tb) < best) {
          best = {ta, tb};
          result.point = *hit;
        }
      }
    }
    begin = end;
  }
  if (best.first >= 0) {
    result.intersects = true;
    result.element_a = s.element[static_cast<std::size_t>(best.first)];
    result.element_b = s.element[static_cast<std::size_t>(best.second)];
  }
  return result;
}

}  // namespace

SelfIntersection find_self_intersection(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const SelfIntersectionOptions& options) {
  validate(model, x, options, "find_self_intersection");
  return find_self_intersection_unchecked(model, x, options);
}

double signed_self_gap(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                       const SelfIntersectionOptions& options) {
  validate(model, x, options, "signed_self_gap");
  SelfDistanceOptions distance_options;
  distance_options.exclusion_radius = options.exclusion_radius;
  distance_options.samples_per_edge = options.samples_per_edge;
  distance_options.core_radius = options.core_radius;
  distance_options.core_center = options.core_center;
  const double d = smallest_self_distance(model, x, distance_options).distance;
  return signed_gap(find_self_intersection_unchecked(model, x, options), d);
}

double signed_gap(const SelfIntersection& intersection, double distance) {
  // An admissible intersecting pair has admissible sample pairs, so distance is finite then.
  return intersection.intersects ? -std::max(distance, std::numeric_limits<double>::min())
                                 : distance;
}

}  // namespace growshell
