// The list of particle shapes: the one place a shape is registered (docs/architecture.md, "Adding a
// shape"). A shape is one header, geometry/shapes/<name>.hpp, specialising ShapeTraits (its
// parameters and their JSON, radii, volume, motion bound, placement extents and its overlap tests
// with the shapes before it here), plus its entry below: its name in ANISODYN_SHAPES and its header
// in the include block. The enum, the parser registry, the JSON output, the per-shape queries and
// the overlap dispatch are all generated from this list.
//
// Keep the order: it fixes the enum values (stored nowhere, but shown in messages), and a shape
// registers its overlap tests against itself and the shapes before it.
//
// This file is read twice, like a .def file (no include guard): geometry/shape.hpp takes the names
// to make the enum; geometry/shapes.hpp defines ANISODYN_SHAPE_HEADERS first and gets the headers.
#ifndef ANISODYN_SHAPES
#define ANISODYN_SHAPES(X) \
  X(Sphere)                \
  X(Cuboid)                \
  X(Spherocylinder)        \
  X(Ellipsoid)
#endif

#ifdef ANISODYN_SHAPE_HEADERS
#include "anisodyn/geometry/shapes/sphere.hpp"
#include "anisodyn/geometry/shapes/cuboid.hpp"
#include "anisodyn/geometry/shapes/spherocylinder.hpp"
#include "anisodyn/geometry/shapes/ellipsoid.hpp"
#endif
