#pragma once
/// \file
/// Loop's subdivision and limit masks for a vertex of any valence.
///
/// Loop (1987) with his original vertex weight: a vertex of valence n with neighbours x_k moves to
///   (1 - n beta(n)) x + beta(n) sum_k x_k,  beta(n) = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n,
/// a new edge point is 3/8 of each end plus 1/8 of each opposite vertex, and the limit position of
/// the vertex is (1 - n chi(n)) x + chi(n) sum_k x_k with chi(n) = 1 / (n + 3 / (8 beta(n))).
/// For n = 6 these are the box-spline rules of the regular patch (beta = 1/16, chi = 1/12).

namespace growshell {

/// beta(n): weight of each neighbour in the new position of a vertex of valence n (n >= 3).
double loop_vertex_neighbour_weight(int valence);

/// chi(n): weight of each neighbour in the limit position of a vertex of valence n (n >= 3).
double loop_limit_neighbour_weight(int valence);

/// The subdominant eigenvalue lambda(n) = 3/8 + cos(2 pi / n) / 4 of the subdivision matrix
/// around a vertex of valence n: one subdivision step shrinks the one-ring's tangent-plane
/// spread by this factor (1/2 for n = 6).
double loop_subdominant_eigenvalue(int valence);

}  // namespace growshell
