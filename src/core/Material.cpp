#include "core/Material.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace rondel {

std::string material_table_text(const std::vector<Material>& materials) {
  std::string out;
  char buf[160];
  for (const Material& m : materials) {
    std::snprintf(buf, sizeof buf, " %a %a %a %a\n", m.density, m.thickness, m.youngs_modulus, m.poisson_ratio);
    out += m.name + " " + body_name(m.body) + buf;
  }
  return out;
}

std::vector<Material> parse_material_table(const std::string& text) {
  std::vector<Material> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::istringstream f(line);
    Material m;
    std::string body, v[4];
    const BodyName* named = nullptr;
    if (f >> m.name >> body >> v[0] >> v[1] >> v[2] >> v[3])
      for (const BodyName& b : kBodyNames)
        if (body == b.name) named = &b;
    if (!named) throw std::invalid_argument("malformed material line '" + line + "'");
    m.body = named->body;
    double* dst[4] = {&m.density, &m.thickness, &m.youngs_modulus, &m.poisson_ratio};
    for (int k = 0; k < 4; ++k) *dst[k] = std::strtod(v[k].c_str(), nullptr);
    out.push_back(m);
  }
  return out;
}

}  // namespace rondel
