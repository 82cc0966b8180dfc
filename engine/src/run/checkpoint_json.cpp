#include "anisodyn/run/checkpoint_json.hpp"

namespace anisodyn::run {

namespace {

std::vector<Vec3> unflatten(const std::vector<double>& xs) {
  std::vector<Vec3> out(xs.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(xs[3 * i], xs[3 * i + 1], xs[3 * i + 2]);
  return out;
}

}  // namespace

nlohmann::json vec3_json(const Vec3& v) { return std::vector<double>{v.x(), v.y(), v.z()}; }

Vec3 vec3_from_json(const nlohmann::json& j) {
  const auto v = j.get<std::vector<double>>();
  return Vec3(v.at(0), v.at(1), v.at(2));
}

nlohmann::json mat3_json(const Mat3& m) { return std::vector<double>(m.data(), m.data() + 9); }

Mat3 mat3_from_json(const nlohmann::json& j) {
  const auto v = j.get<std::vector<double>>();
  return Eigen::Map<const Mat3>(v.data());
}

std::vector<double> flatten(const std::vector<Vec3>& vs) {
  std::vector<double> out;
  out.reserve(3 * vs.size());
  for (const Vec3& v : vs) out.insert(out.end(), {v.x(), v.y(), v.z()});
  return out;
}

nlohmann::json body_forces_json(const BodyForces& f) {
  return {{"force", flatten(f.force)}, {"torque", flatten(f.torque)}, {"energy", f.energy}, {"virial", mat3_json(f.virial)}};
}

BodyForces body_forces_from_json(const nlohmann::json& j) {
  BodyForces f;
  f.force = unflatten(j.at("force").get<std::vector<double>>());
  f.torque = unflatten(j.at("torque").get<std::vector<double>>());
  f.energy = j.at("energy").get<double>();
  f.virial = mat3_from_json(j.at("virial"));
  return f;
}

}  // namespace anisodyn::run
