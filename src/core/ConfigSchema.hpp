#pragma once
#include <boost/program_options.hpp>

#include "core/LawSpec.hpp"

namespace rondel {

// Every configuration key, declared once with its default, unit and meaning (docs/design.md section 8); the
// law blocks come from the catalog (each law declares its parameters next to its equations).
boost::program_options::options_description config_schema(const LawCatalog& laws);

}  // namespace rondel
