#pragma once
#include <boost/program_options.hpp>

namespace rondel {

// Every configuration key, declared once with its default, unit and meaning (DESIGN.md section 8).
boost::program_options::options_description config_schema();

}  // namespace rondel
