// Hidden helper tool: writes an example H5MD trajectory (two species, a box that changes between
// frames as under NPT, observables sampled more and less often than frames) so that external
// readers (MDAnalysis in tests/integration/h5md_mdanalysis.py) can be checked against it.
//
//   anisodyn-h5md-example OUTPUT.h5 [--particles N] [--frames F] [--seed S]
//
// Prints a JSON summary (particle count, frames, box edges, steps and times) on stdout.
// --describe prints its description (tool/description.hpp) and exits, as for every executable.
#include <cstdlib>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;

namespace {

tool::ToolInfo info() {
  tool::Description d;
  d.role = tool::Role::Example;
  d.inputs = {"none", 0, 0, "none"};
  d.output = {"trajectory", "H5MD", "an example trajectory (positional OUTPUT, not --output): two species, an NPT-like box, "
                                   "observables sampled more and less often than frames", nullptr};
  // Takes no configuration file: --particles N, --frames F and --seed S on its own command line.
  d.cost = tool::negligible_cost("milliseconds");
  return {"anisodyn-h5md-example", "an example H5MD trajectory for checking external readers",
          "usage: anisodyn-h5md-example OUTPUT.h5 [--particles N] [--frames F] [--seed S]", d};
}

long parse_count(const std::string& option, const char* text) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (!end || *end != '\0' || v < 1) throw InputError("", option, std::string("expected a positive integer, got '") + text + "'");
  return v;
}

int run(int argc, char** argv) {
  std::string output;
  long n = 40, frames = 4, seed = 7;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--particles" || a == "--frames" || a == "--seed") && i + 1 < argc) {
      const long v = parse_count(a, argv[++i]);
      (a == "--particles" ? n : a == "--frames" ? frames : seed) = v;
    } else if (a == "--help" || a == "-h") {
      std::cout << info().usage_notes << "\n";
      return 0;
    } else if (a == "--describe") {
      std::cout << tool::describe(info()).dump(2) << std::endl;
      return 0;
    } else if (!a.empty() && a[0] != '-' && output.empty()) {
      output = a;
    } else {
      throw InputError("", "", "unexpected argument '" + a + "' (see --help)");
    }
  }
  if (output.empty()) throw InputError("", "", "missing OUTPUT path (see --help)");
  tool::check_output_writable(output);

  State s;
  Species board;
  board.name = "board";
  board.shape = Shape::cuboid(1.0, 3.0, 12.0);
  board.D_trans = Vec3(0.05, 0.06, 0.08);
  board.D_rot = Vec3(0.002, 0.003, 0.01);
  Species bead;
  bead.name = "bead";
  bead.shape = Shape::sphere(2.0);
  bead.D_trans = Vec3::Constant(0.1);
  bead.D_rot = Vec3::Constant(0.075);
  s.species = {board, bead};
  s.box = Box(Vec3(30.0, 32.0, 34.0));

  Rng rng(static_cast<std::uint64_t>(seed), 0);
  for (long i = 0; i < n; ++i) {
    const Vec3 r(rng.uniform(0, 30.0), rng.uniform(0, 32.0), rng.uniform(0, 34.0));
    s.particles.add(i % 3 == 0 ? 1 : 0, r, uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()), 1000 + i);
  }

  io::H5mdHeader header;
  header.parameters = {{"example", true}, {"particles", n}, {"frames", frames}, {"seed", seed}};
  header.provenance = tool::make_provenance("anisodyn-h5md-example", tool::argv_vector(argc, argv), {});
  header.species = s.species;
  io::H5mdWriter writer(output, header);
  writer.set_observable_attribute("packing_fraction", "units", "1");
  writer.set_observable_attribute("packing_fraction", "definition", "sum of particle volumes / box volume");

  nlohmann::json summary = {{"n_atoms", n}, {"frames", frames}, {"box", nlohmann::json::array()},
                            {"steps", nlohmann::json::array()}, {"times", nlohmann::json::array()}};
  const int sweeps_per_frame = 4;
  for (long f = 0; f < frames; ++f) {
    for (int k = 0; k < sweeps_per_frame; ++k) {
      const std::int64_t sweep = f * sweeps_per_frame + k;
      // Random displacements, wrapped with image counting; an NPT-like isotropic box change.
      const double scale = 1.0 + 0.01 * rng.uniform(-1, 1);
      s.box.set_edges(s.box.edges() * scale);
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        Vec3 r = s.particles.position(i) * scale + Vec3(rng.normal(), rng.normal(), rng.normal());
        Int3 img = s.particles.image(i);
        s.box.wrap(r, img);
        s.particles.set_position(i, r);
        s.particles.set_image(i, img);
        s.particles.set_orientation(i, rotate_in_body_frame(s.particles.orientation(i),
                                                            0.1 * Vec3(rng.normal(), rng.normal(), rng.normal())));
      }
      s.step = (sweep + 1) * 10;
      s.time = 0.5 * static_cast<double>(sweep + 1);
      // Sampled every sweep: more rows than frames (stays in /observables).
      writer.append_observable("packing_fraction", s.step, s.time, s.packing_fraction());
      writer.append_observable("acceptance", s.step, s.time, std::vector<double>{rng.uniform(), rng.uniform()});
    }
    writer.append_frame(s);
    summary["box"].push_back({s.box.edges().x(), s.box.edges().y(), s.box.edges().z()});
    summary["steps"].push_back(s.step);
    summary["times"].push_back(s.time);
    // Sampled every other frame: fewer rows than frames (moved to /anisodyn/observables).
    if (f % 2 == 1) writer.append_observable("sparse_energy", s.step, s.time, rng.normal());
  }
  writer.write_checkpoint({{"rng", {{"seed", seed}, {"stream", 0}, {"counter", rng.state().counter}}},
                           {"step", s.step}, {"time", s.time}});
  writer.commit();
  std::cout << summary.dump() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const InputError& e) {
    std::cerr << "anisodyn-h5md-example: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "anisodyn-h5md-example: error: " << e.what() << "\n";
    return kExitRuntime;
  }
}
