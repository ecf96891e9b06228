// The energy ledger's terms, declared once (core/LedgerTerms.hpp): each term has one checkpoint attribute
// name and at most one diagnostics.csv column, both unique; the names and the header stay the ones of the
// file format (FORMAT.md, README); a term's value lands in its own column of a diagnostics row; the
// ledger adds exactly the kernel's terms; and a member added without a line in the term list fails here.
// The checkpoint round trip (write, read back) is in tests/parallel/test_ledger_checkpoint.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/Diagnostics.hpp"
#include "core/LedgerTerms.hpp"
#include "physics/EnergyLedger.hpp"

namespace rondel {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string x; std::getline(in, x, ',');) out.push_back(x);
  return out;
}

// Each term set to a distinct value: 1.5, 2.5, ... in the terms' order.
template <class Terms>
void number_terms(Terms& terms) {
  double v = 0.5;
  terms.for_each_term([&v](const LedgerTermInfo&, double& value) { value = (v += 1.0); });
}

TEST(LedgerTerms, CheckpointNamesAreTheFileFormats) {
  std::vector<std::string> names;
  LedgerTerms{}.for_each_term([&](const LedgerTermInfo& t, double) { names.emplace_back(t.name); });
  EXPECT_EQ(names, (std::vector<std::string>{"KE0", "W_g", "W_w", "W_n", "W_t", "W_r", "W_b", "W_cell", "W_driver",
                                             "D_slip", "D_r_plastic", "D_r_dashpot", "E_r_break", "D_n_hyst",
                                             "E_b_break", "D_damping", "scale", "n_b_tension", "n_b_shear"}));
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size()) << "a name appears twice";
}

TEST(LedgerTerms, EachColumnAppearsOnceInTheDiagnosticsHeader) {
  const std::vector<std::string> header = split_csv(DiagnosticsWriter::header());
  EXPECT_EQ(std::set<std::string>(header.begin(), header.end()).size(), header.size()) << "a column appears twice";
  LedgerTerms{}.for_each_term([&](const LedgerTermInfo& t, double) {
    const bool work = (t.uses & kTermWork) != 0, loss = (t.uses & kTermDissipation) != 0;
    const bool count = (t.uses & kTermCount) != 0;
    EXPECT_LE(int{work} + int{loss} + int{count}, 1) << t.name << " is more than one of a work, a loss and a count";
    EXPECT_EQ(t.column.empty(), !work && !loss && !count)
        << t.name << ": a column exactly for the works, dissipations and counts";
    EXPECT_TRUE(!(t.uses & kTermKernel) || (t.uses & kTermRankShare)) << t.name << ": a kernel term is a rank share";
    if (t.column.empty()) return;
    EXPECT_EQ(std::count(header.begin(), header.end(), std::string(t.column)), 1) << t.column;
  });
}

TEST(LedgerTerms, DiagnosticsHeaderIsTheFileFormats) {
  EXPECT_EQ(DiagnosticsWriter::header(),
            "step,time,ke_trans,ke_rot,contacts,wall_contacts,coordination,max_overlap_ratio,W_gravity,W_walls,"
            "W_normal,W_tangential,W_rolling,W_bonds,W_cell,W_driver,E_stored,D_slip,D_rolling_plastic,"
            "D_rolling_dashpot,E_rolling_break,D_normal_hysteresis,E_bond_break,D_damping,D_other,ledger_residual,"
            "imbalance,ghost_fraction,migrated,bonds,bond_breaks_tension,bond_breaks_shear");
}

TEST(LedgerTerms, ATermsValueLandsInItsOwnDiagnosticsColumn) {
  DiagnosticsRow row;
  number_terms(row);
  row.E_stored = 100.25;
  row.D_other = 200.25;
  const std::vector<std::string> header = split_csv(DiagnosticsWriter::header());
  const std::vector<std::string> fields = split_csv(DiagnosticsWriter::format(row));
  ASSERT_EQ(fields.size(), header.size());
  auto field = [&](const std::string& column) {
    const auto at = std::find(header.begin(), header.end(), column);
    return at == header.end() ? std::string("<no column>") : fields[static_cast<std::size_t>(at - header.begin())];
  };
  row.for_each_term([&](const LedgerTermInfo& t, double value) {
    if (t.column.empty()) return;
    std::ostringstream s;
    s.precision(12);
    s << value;
    EXPECT_EQ(field(std::string(t.column)), s.str()) << t.name;
  });
  EXPECT_EQ(field("E_stored"), "100.25");
  EXPECT_EQ(field("D_other"), "200.25");
}

TEST(LedgerTerms, EveryMemberIsInTheTermList) {
  std::size_t terms = 0;
  LedgerTerms{}.for_each_term([&](const LedgerTermInfo&, double) { ++terms; });
  EXPECT_EQ(sizeof(LedgerTerms), terms * sizeof(double))
      << "LedgerTerms has a member that LedgerTerms::visit_terms does not visit";
}

TEST(EnergyLedger, AddsTheKernelsTermsGravityAndDamping) {
  EnergyLedger ledger;
  number_terms(ledger);
  const EnergyLedger before = ledger;
  LedgerStep step;
  number_terms(step);
  ledger.add(step, 0.25, 0.125);
  LedgerTerms::visit_terms(
      [](const LedgerTermInfo& t, double now, double was, double booked) {
        if (t.name == "W_g")
          EXPECT_EQ(now, was + 0.25);
        else if (t.name == "D_damping")
          EXPECT_EQ(now, was + 0.125);
        else if (t.uses & kTermKernel)
          EXPECT_EQ(now, was + booked) << t.name;
        else
          EXPECT_EQ(now, was) << t.name << " is not booked per step";
      },
      ledger, before, step);
}

TEST(EnergyLedger, DOtherIsMinusWcMinusStoredMinusEachDissipation) {
  EnergyLedger g;
  g.W_n = -0.7;
  g.W_t = -0.11;
  g.W_r = -0.013;
  g.D_slip = 0.3;
  g.D_r_plastic = 0.07;
  g.D_r_dashpot = 0.011;
  g.E_r_break = 0.0017;
  const double E_stored = 0.19;
  // The historical expression, operation for operation (the CSV's bits must not change).
  const double expected = -g.W_c() - E_stored - g.D_slip - g.D_r_plastic - g.D_r_dashpot - g.E_r_break;
  EXPECT_EQ(g.D_other(E_stored), expected);
  // The local damping is not a part of -W_c: it leaves D_other alone.
  g.D_damping = 0.5;
  EXPECT_EQ(g.D_other(E_stored), expected);
}

// The residual adds the damping's loss back: KE = KE0 + W_g + W_w + W_c - D_damping closes to 0; with
// D_damping = 0 the residual is the historical expression's, bit for bit.
TEST(EnergyLedger, ResidualCountsTheDampingLoss) {
  EnergyLedger g;
  g.KE0 = 1.0;
  g.W_g = 3.0;
  g.W_w = 0.5;
  g.W_n = -0.75;
  g.W_t = -0.25;
  const double KE_undamped = 3.5;
  EXPECT_EQ(g.absolute_residual(KE_undamped), 0.0);
  EXPECT_EQ(g.absolute_residual(KE_undamped + 0.1), std::fabs(KE_undamped + 0.1 - g.KE0 - g.W_g - g.W_w - g.W_c()));
  g.D_damping = 1.25;
  EXPECT_EQ(g.absolute_residual(KE_undamped - 1.25), 0.0);
  EXPECT_EQ(g.absolute_residual(KE_undamped), 1.25);
}

}  // namespace
}  // namespace rondel
