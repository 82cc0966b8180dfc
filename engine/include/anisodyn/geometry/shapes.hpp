#pragma once
// Every shape's header (geometry/shape_list.hpp), for the code that dispatches over them: the shape
// queries (shape.cpp), the parser registry and the overlap dispatch.
#include "anisodyn/geometry/shape.hpp"

#define ANISODYN_SHAPE_HEADERS
#include "anisodyn/geometry/shape_list.hpp"
#undef ANISODYN_SHAPE_HEADERS

namespace anisodyn {

/// Reads a shape object {"type": name or alias, parameters…} (InputError naming the JSON path
/// otherwise).
Shape parse_shape(tool::ConfigNode node);

}  // namespace anisodyn
