// The second half of the firefly guard (statmc/core/firefly_guard.h): after the kernel
// has filtered every pixel with fireflies kept out, each firefly joins the averages of
// the neighbours that accept it, scaled so that it gives away no more than its own value.
#pragma once

#include <vector>

#include "filter_layout.h"

namespace statmc::detail {

/// A firefly f joins centre j's average with weight s_f·W_jf, where W_jf is the filter's
/// weight (membership test, spatial and guide terms) and
///     s_f = min(1, 1 / c_f),   c_f = Σ_j W_jf / W_j   (j over f's disk and f itself)
/// is the share of F_f that the paper's filter would hand out over the whole image (W_j:
/// centre j's weight sum in the paper's filter, fireflies included). Where neighbours
/// average many members, c_f ≈ 1 and this is the paper's filter; where they have few
/// (detail, high spp), c_f ≫ 1: the paper's filter would copy the firefly into every pixel
/// of its disk.
/// Every sum runs in a fixed order, so the result does not depend on threads.
/// `out` holds the kernel's output and `weight_sum` its W (fireflies excluded); both are
/// updated, and `members` too where it is not null.
void spread_fireflies(const FilterLayout& layout, const std::vector<Plane>& out,
                      Plane weight_sum, Plane members);

}  // namespace statmc::detail
