#include "solvers/stability/vertex_symmetry_group.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace growshell {

namespace {

bool same(const VertexSymmetry& a, const VertexSymmetry& b) {
  return a.signs == b.signs && a.image == b.image;
}

/// a after b: v -> a(b(v)), signs multiplied (the S are diagonal, so they commute).
VertexSymmetry compose(const VertexSymmetry& a, const VertexSymmetry& b) {
  VertexSymmetry out;
  out.signs = a.signs.cwiseProduct(b.signs);
  out.image.resize(b.image.size());
  for (std::size_t v = 0; v < b.image.size(); ++v)
    out.image[v] = a.image[static_cast<std::size_t>(b.image[v])];
  return out;
}

void validate(Eigen::Index vertex_count, const VertexSymmetry& g, std::size_t which) {
  const std::string name = "VertexSymmetryGroup: generator " + std::to_string(which);
  if (static_cast<Eigen::Index>(g.image.size()) != vertex_count)
    throw std::invalid_argument(name + " maps " + std::to_string(g.image.size()) +
                                " vertices, expected " + std::to_string(vertex_count));
  std::vector<char> hit(g.image.size(), 0);
  for (const int u : g.image) {
    if (u < 0 || u >= vertex_count || hit[static_cast<std::size_t>(u)])
      throw std::invalid_argument(name + " is not a permutation of the vertices");
    hit[static_cast<std::size_t>(u)] = 1;
  }
  for (int c = 0; c < 3; ++c)
    if (g.signs(c) != 1.0 && g.signs(c) != -1.0)
      throw std::invalid_argument(name + ": signs must be +1 or -1");
}

}  // namespace

VertexSymmetryGroup::VertexSymmetryGroup(Eigen::Index vertex_count,
                                         std::vector<VertexSymmetry> generators)
    : vertex_count_(vertex_count), generators_(std::move(generators)) {
  if (vertex_count < 1) throw std::invalid_argument("VertexSymmetryGroup: no vertices");
  if (generators_.size() > 16)
    throw std::invalid_argument("VertexSymmetryGroup: more than 16 generators");
  for (std::size_t k = 0; k < generators_.size(); ++k) validate(vertex_count, generators_[k], k);
  VertexSymmetry identity;
  identity.image.resize(static_cast<std::size_t>(vertex_count));
  for (Eigen::Index v = 0; v < vertex_count; ++v)
    identity.image[static_cast<std::size_t>(v)] = static_cast<int>(v);
  elements_.push_back(std::move(identity));
  words_.push_back(0u);
  // Breadth-first closure; products_[g][s] is the index of s after g.
  for (std::size_t g = 0; g < elements_.size(); ++g) {
    products_.emplace_back(generators_.size(), -1);
    for (std::size_t s = 0; s < generators_.size(); ++s) {
      VertexSymmetry h = compose(generators_[s], elements_[g]);
      std::size_t found = 0;
      while (found < elements_.size() && !same(elements_[found], h)) ++found;
      if (found == elements_.size()) {
        if (elements_.size() == 64)
          throw std::invalid_argument(
              "VertexSymmetryGroup: the generators span more than 64 elements");
        elements_.push_back(std::move(h));
        words_.push_back(words_[g] ^ (1u << s));
      }
      products_[g][s] = static_cast<int>(found);
    }
  }
}

std::vector<int> VertexSymmetryGroup::word_signs(const std::vector<int>& generator_signs) const {
  std::vector<int> chi(elements_.size(), 1);
  for (std::size_t g = 0; g < elements_.size(); ++g)
    for (std::size_t s = 0; s < generators_.size(); ++s)
      if (words_[g] & (1u << s)) chi[g] *= generator_signs[s];
  return chi;
}

bool VertexSymmetryGroup::is_character(const std::vector<int>& generator_signs) const {
  if (generator_signs.size() != generators_.size()) return false;
  for (const int sign : generator_signs)
    if (sign != 1 && sign != -1) return false;
  const std::vector<int> chi = word_signs(generator_signs);
  for (std::size_t g = 0; g < elements_.size(); ++g)
    for (std::size_t s = 0; s < generators_.size(); ++s)
      if (chi[static_cast<std::size_t>(products_[g][s])] != generator_signs[s] * chi[g])
        return false;
  return true;
}

Eigen::SparseMatrix<double> VertexSymmetryGroup::class_basis(
    const std::vector<int>& generator_signs) const {
  if (generator_signs.size() != generators_.size())
    throw std::invalid_argument("VertexSymmetryGroup::class_basis: " +
                                std::to_string(generator_signs.size()) + " signs for " +
                                std::to_string(generators_.size()) + " generators");
  if (!is_character(generator_signs))
    throw std::invalid_argument(
        "VertexSymmetryGroup::class_basis: the signs are not a character of the group (each "
        "must be +1 or -1, and products of generators must get the product of their signs)");
  const std::vector<int> chi = word_signs(generator_signs);

  // One column per dof orbit: sum_g chi(g) S_g(c) e_{(g(v), c)}, none where the orbit meets
  // a dof with both signs.
  const Eigen::Index n = 3 * vertex_count_;
  std::vector<char> visited(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::Index column = 0;
  for (Eigen::Index dof = 0; dof < n; ++dof) {
    if (visited[static_cast<std::size_t>(dof)]) continue;
    const Eigen::Index v = dof / 3;
    const int c = static_cast<int>(dof % 3);
    std::map<Eigen::Index, double> orbit;
    for (std::size_t g = 0; g < elements_.size(); ++g) {
      const Eigen::Index image = 3 * elements_[g].image[static_cast<std::size_t>(v)] + c;
      orbit[image] += chi[g] * elements_[g].signs(c);
      visited[static_cast<std::size_t>(image)] = 1;
    }
    double norm2 = 0.0;
    for (const auto& [i, a] : orbit) norm2 += a * a;
    if (norm2 == 0.0) continue;
    const double scale = 1.0 / std::sqrt(norm2);
    for (const auto& [i, a] : orbit)
      if (a != 0.0) entries.emplace_back(i, column, a * scale);
    ++column;
  }
  Eigen::SparseMatrix<double> basis(n, column);
  basis.setFromTriplets(entries.begin(), entries.end());
  basis.makeCompressed();
  return basis;
}

std::string VertexSymmetryGroup::why_classes_do_not_split() const {
  const std::size_t k = generators_.size();
  for (std::size_t s = 0; s < k; ++s) {
    if (products_[static_cast<std::size_t>(products_[0][s])][s] != 0)
      return "generator " + std::to_string(s) + " is not an involution";
    for (std::size_t t = 0; t < s; ++t)
      if (!same(compose(generators_[s], generators_[t]), compose(generators_[t], generators_[s])))
        return "generators " + std::to_string(t) + " and " + std::to_string(s) +
               " do not commute";
  }
  if (elements_.size() != (std::size_t{1} << k)) return "a generator is generated by the others";
  return "";
}

bool VertexSymmetryGroup::classes_split_space() const { return why_classes_do_not_split().empty(); }

std::vector<std::vector<int>> VertexSymmetryGroup::splitting_characters() const {
  const std::string why = why_classes_do_not_split();
  if (!why.empty())
    throw std::invalid_argument("VertexSymmetryGroup::splitting_characters: " + why);
  const std::size_t k = generators_.size();
  std::vector<std::vector<int>> characters;
  for (unsigned mask = 0; mask < (1u << k); ++mask) {
    std::vector<int> signs(k, 1);
    for (std::size_t s = 0; s < k; ++s)
      if (mask & (1u << s)) signs[s] = -1;
    characters.push_back(std::move(signs));
  }
  return characters;
}

}  // namespace growshell
