// The lights, the camera and positions in metres of a JSON scene (lights_camera_json.h).
#include "scene_io/lights_camera_json.h"

#include <cmath>
#include <string>

#include "scene_io/obj_text_check.h"

namespace pm {

namespace {

const int kMaxResolution = 16384;

float length(const Float3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

// A spot light's cone angle in degrees, as radians: in [0, 90] degrees.
float read_cone_angle(const JsonField& field) {
  const double degrees = field.finite_number();
  if (!(degrees >= 0 && degrees <= 90)) field.fail("must be in [0, 90] degrees, got " + describe_json_value(field.value()));
  return static_cast<float>(degrees * M_PI / 180.0);
}

LightDesc read_light(const JsonField& field, size_t index, double meters_per_unit) {
  field.expect_object_with_keys({"name", "type", "position", "power", "direction", "inner_cone_angle", "outer_cone_angle"});
  LightDesc light;
  light.name = field.has("name") ? field.member("name").non_empty_string() : "light" + std::to_string(index);
  if (field.has("type")) {
    const JsonField type = field.member("type");
    const std::string name = type.non_empty_string();
    if (name == "spot") light.type = LightType::spot;
    else if (name != "point") type.fail("expected \"point\" or \"spot\", got '" + name + "'");
  }
  light.position = read_position_in_metres(field.member("position"), meters_per_unit);
  const JsonField power = field.member("power");
  light.power = power.float3();
  const float watts[3] = {light.power.x, light.power.y, light.power.z};
  for (size_t c = 0; c < 3; ++c)
    if (watts[c] < 0) power.element(c).fail("must be >= 0 W, got " + describe_json_value(power.element(c).value()));
  if (light.type != LightType::spot) {
    for (const char* key : {"direction", "inner_cone_angle", "outer_cone_angle"})
      if (field.has(key)) field.member(key).fail("only a spot light has this key (\"type\": \"spot\")");
    return light;
  }
  const JsonField direction = field.member("direction");
  light.direction = direction.float3();
  if (!(length(light.direction) > 0)) direction.fail("must not be zero");
  light.outer_cone = field.has("outer_cone_angle") ? read_cone_angle(field.member("outer_cone_angle")) : float(M_PI / 4);
  light.inner_cone = field.has("inner_cone_angle") ? read_cone_angle(field.member("inner_cone_angle")) : 0.0f;
  if (!(light.inner_cone < light.outer_cone)) {
    const JsonField where = field.has("inner_cone_angle") ? field.member("inner_cone_angle") : field.member("outer_cone_angle");
    where.fail("the inner cone angle must be below the outer one (" + std::to_string(light.inner_cone * 180.0 / M_PI) +
               " >= " + std::to_string(light.outer_cone * 180.0 / M_PI) + " degrees)");
  }
  return light;
}

}  // namespace

// The same bound as OBJ vertex coordinates, now in metres.
Float3 position_in_metres(const Float3& units, double meters_per_unit, const JsonField& field) {
  const double m[3] = {units.x * meters_per_unit, units.y * meters_per_unit, units.z * meters_per_unit};
  for (double v : m) {
    if (!(std::fabs(v) <= kMaxObjCoordinate))
      field.fail("a position is " + describe_json_value(v) + " m from the origin once converted to metres; at most 1e15 m renders");
  }
  return Float3{static_cast<float>(m[0]), static_cast<float>(m[1]), static_cast<float>(m[2])};
}

Float3 read_position_in_metres(const JsonField& field, double meters_per_unit) {
  return position_in_metres(field.float3(), meters_per_unit, field);
}

std::vector<LightDesc> read_lights(const JsonField& root, double meters_per_unit) {
  std::vector<LightDesc> result;
  if (!root.has("lights")) return result;
  const JsonField lights = root.member("lights");
  const size_t count = lights.expect_array();
  for (size_t i = 0; i < count; ++i) result.push_back(read_light(lights.element(i), i, meters_per_unit));
  return result;
}

CameraDesc read_camera(const JsonField& root, double meters_per_unit) {
  const JsonField field = root.member("camera");
  field.expect_object_with_keys({"position", "look_at", "up", "vertical_fov", "resolution"});
  CameraDesc camera;  // defaults: up +y, 45 degrees, 512 x 512
  camera.position = read_position_in_metres(field.member("position"), meters_per_unit);
  const JsonField look_at = field.member("look_at");
  camera.look_at = read_position_in_metres(look_at, meters_per_unit);
  const Float3 view{camera.look_at.x - camera.position.x, camera.look_at.y - camera.position.y,
                    camera.look_at.z - camera.position.z};
  const float view_length = length(view);
  if (!(view_length > 0)) look_at.fail("equals camera.position (no view direction)");

  // up is a direction, so it is not scaled. It must leave a "right" axis: |view x up| is
  // |sin| of their angle times both lengths, and near zero means (anti)parallel.
  const bool up_given = field.has("up");
  if (up_given) camera.up = field.member("up").float3();
  const float up_length = length(camera.up);
  const Float3 cross{view.y * camera.up.z - view.z * camera.up.y, view.z * camera.up.x - view.x * camera.up.z,
                     view.x * camera.up.y - view.y * camera.up.x};
  if (up_given && !(up_length > 0)) field.member("up").fail("must not be the zero vector");
  if (!(length(cross) > 1e-6f * view_length * up_length)) {
    if (up_given) field.member("up").fail("is parallel to the view direction (look_at - position)");
    field.fail("the default up [0, 1, 0] is parallel to the view direction; set camera.up");
  }

  if (field.has("vertical_fov")) {
    const JsonField fov = field.member("vertical_fov");
    const double degrees = fov.finite_number();
    if (!(degrees > 0 && degrees < 180))
      fov.fail("must be in (0, 180) degrees, got " + describe_json_value(fov.value()));
    camera.vertical_fov_degrees = static_cast<float>(degrees);
  }
  if (field.has("resolution")) {
    const JsonField resolution = field.member("resolution");
    resolution.expect_array(2);
    camera.width = static_cast<int>(resolution.element(0).integer_in(1, kMaxResolution));
    camera.height = static_cast<int>(resolution.element(1).integer_in(1, kMaxResolution));
  }
  return camera;
}

}  // namespace pm
