#include "anisodyn/run/field_config.hpp"

#include "anisodyn/io/body_axis_choice.hpp"

namespace anisodyn::run {

namespace {

DipoleConfig parse_dipoles(tool::ConfigNode& d) {
  DipoleConfig c;
  c.gamma = d.positive("gamma");
  c.species = d.strings("species");
  if (c.species.empty()) d.fail("species", "expected at least one species name");
  c.minimum_image_only = d.boolean("minimum_image_only", false);
  d.reject_unless(!c.minimum_image_only, "accuracy",
                  "with minimum_image_only (the truncated sum to L/2 has no Ewald parameters to choose)");
  c.accuracy = d.positive("accuracy", 1e-5);
  if (c.accuracy >= 0.1) d.fail("accuracy", "expected a relative accuracy below 0.1 (default 1e-5)");
  return c;
}

}  // namespace

FieldConfig parse_field_config(tool::ConfigNode& cfg, FieldUse use) {
  FieldConfig f;
  auto field = cfg.optional_object("field");
  if (!field) return f;
  const Vec3 dir = field->vec3("direction", Vec3::UnitX());
  if (!(dir.norm() > 0.0)) field->fail("direction", "expected a non-zero vector");
  f.orientational.direction = dir.normalized();
  const bool constant = use == FieldUse::Constant;
  const std::string on_throughout = "here: this tool keeps its field on for the whole run";
  field->reject_unless(!constant, "initially", on_throughout);
  field->reject_unless(!constant, "dipoles", on_throughout + " and has no dipolar interaction");
  if (!field->has("orientational") && !field->has("dipoles"))
    field->fail("", std::string("an 'orientational' field") + (constant ? "" : " or 'dipoles'") +
                        " (a field block without one has no effect)");
  if (!constant) {
    f.initially_on = field->choice("initially", {"on", "off"}, "off") == "on";
    field->reject_unless(field->has("orientational"), "check_direction",
                         "without an orientational field (it turns the field perpendicular to the nematic director)");
    f.check_direction = field->boolean("check_direction", true);
  } else {
    field->reject_unless(false, "check_direction", on_throughout + " (the check acts when a field is switched on)");
  }
  if (auto o = field->optional_object("orientational")) {
    f.orientational.strength = o->positive("strength");
    f.orientational.body_axis = io::choose_body_axis(*o, "axis", "W", false);
  }
  if (auto d = field->optional_object("dipoles")) f.dipoles = parse_dipoles(*d);
  return f;
}

}  // namespace anisodyn::run
