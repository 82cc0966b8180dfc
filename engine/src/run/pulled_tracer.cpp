#include "anisodyn/run/pulled_tracer.hpp"

#include "anisodyn/core/error.hpp"

namespace anisodyn::run {

PulledTracerSpec parse_pulled_tracer(tool::ConfigNode& node) {
  PulledTracerSpec spec;
  spec.species = node.string("species");
  spec.peclet = node.number("pe");
  if (spec.peclet < 0.0) node.fail("pe", "expected a Péclet number ≥ 0");
  if (node.has("axis")) {
    const std::string axis = node.string("axis");
    if (axis != "x" && axis != "y" && axis != "z") node.fail("axis", "expected one of x, y, z");
    spec.axis = axis[0] - 'x';
  }
  spec.record_every = node.positive_integer("record_every", 1);
  return spec;
}

std::size_t find_pulled_tracer(const PulledTracerSpec& spec, const State& state, const std::string& file) {
  const int s = species_index(state.species, spec.species);
  if (s < 0) throw InputError(file, "tracer.species", "unknown species '" + spec.species + "'");
  std::size_t count = 0, particle = 0;
  for (std::size_t i = 0; i < state.particles.size(); ++i)
    if (state.particles.species[i] == s) {
      ++count;
      particle = i;
    }
  if (count != 1)
    throw InputError(file, "tracer.species", "expected a species with exactly one particle (the pulled tracer); '" + spec.species +
                                                 "' has " + std::to_string(count));
  if (state.species[static_cast<std::size_t>(s)].shape.is_anisotropic())
    throw InputError(file, "tracer.species", "expected a sphere: the pulled tracer does not rotate");
  return particle;
}

double pulled_tracer_beta_force(const PulledTracerSpec& spec, const State& state, std::size_t particle) {
  const auto s = static_cast<std::size_t>(state.particles.species[particle]);
  return spec.peclet / (0.5 * state.species[s].shape.diameter);
}

void record_tracer_position(io::H5mdWriter& out, const State& state, std::size_t particle, std::int64_t step, double time) {
  const Vec3 r = state.box.unwrap(state.particles.position(particle), state.particles.image(particle));
  out.append_observable("tracer_position", step, time, std::vector<double>{r.x(), r.y(), r.z()});
}

void describe_tracer_position(io::H5mdWriter& out) {
  out.set_observable_attribute("tracer_position", "units", "length unit of the study");
  out.set_observable_attribute("tracer_position", "definition", "unwrapped centre of the pulled tracer");
}

}  // namespace anisodyn::run
