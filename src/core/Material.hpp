#pragma once
// A material (docs/physics.md section 7): its name, density, thickness, body type and the elastic constants
// of the Hertz-Mindlin law. The body type sets the mass and inertia of a disc of radius R:
//   disc   (the cylinder of docs/physics.md section 1): m = rho pi R^2 t,     I = m R^2/2
//   sphere ("spheres in a plane", LIGGGHTS, Lethe):      m = 4/3 pi rho R^3,  I = 2/5 m R^2
#include <numbers>
#include <string>
#include <vector>

namespace rondel {

// The name of the one material of a run given by [material] (not [material.NAME]).
inline constexpr const char* kDefaultMaterial = "default";

struct Material {
  enum class Body { disc, sphere };
  std::string name = kDefaultMaterial;
  double density = 2650.0;
  double thickness = 1.0;
  Body body = Body::disc;
  double youngs_modulus = 0.0;  // [Pa]; 0: not given (only the Hertz-Mindlin laws need it)
  double poisson_ratio = 0.0;   // [-]

  double mass(double R) const {
    return body == Body::disc ? density * std::numbers::pi * R * R * thickness
                              : 4.0 / 3.0 * std::numbers::pi * density * R * R * R;
  }
  double inertia(double m, double R) const { return body == Body::disc ? 0.5 * m * R * R : 0.4 * m * R * R; }
  bool operator==(const Material&) const = default;
};

// The bodies by name (material.body, the material table of a file).
struct BodyName {
  Material::Body body;
  const char* name;
};
inline constexpr BodyName kBodyNames[] = {{Material::Body::disc, "disc"}, {Material::Body::sphere, "sphere"}};
inline const char* body_name(Material::Body b) { return kBodyNames[b == Material::Body::disc ? 0 : 1].name; }

// The index of the material named `name` in `materials`; -1 when none has it.
inline int material_index(const std::vector<Material>& materials, const std::string& name) {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<int>(i);
  return -1;
}

// The material table as text, one material a line: "NAME BODY density thickness youngs_modulus poisson_ratio"
// with the numbers in C99 hexadecimal (bit-exact); the /materials table attribute of a Rondel file (FORMAT.md).
std::string material_table_text(const std::vector<Material>& materials);
// The inverse; throws std::invalid_argument on a malformed line.
std::vector<Material> parse_material_table(const std::string& text);

}  // namespace rondel
