#include "anisodyn/geometry/overlap.hpp"

#include <stdexcept>
#include <string>

namespace anisodyn::overlap_detail {

void throw_unsupported_pair(ShapeKind a, ShapeKind b) {
  throw std::invalid_argument(std::string("overlap: no overlap kernel for the shape pair ") + shape_kind_name(a) +
                              "–" + shape_kind_name(b));
}

}  // namespace anisodyn::overlap_detail
