// `wrc study planar`: the planar contact methods of the paper's Table 1 against the curved
// reference over a set of wheel and rail profiles and poses (the paper's §4.2): Table 3's
// statistics of the differences in L/V and in the forces, the case with the largest difference
// per method as Table 2 and Fig. 19 show it, and the L/V of every case as Fig. 20.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "studies/shipped_files.h"
#include "studies/study_commands.h"
#include "studies/study_common.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/thread_option.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"
#include "wrc/core/toml_reader.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWho = "wrc study planar";
constexpr std::size_t kMaxCases = 100000;

struct PlanarOptions {
  std::string out = "study-planar";
  std::string cases;  // empty: the shipped tables/planar_audit.toml
  int threads = AllCores();
  double lv_limit = 1.0;  // of the curved reference, for the statistics without flange climbing
};

// One wheel on one rail in one pose.
struct AuditCase {
  std::string wheel, rail;
  double y = 0.0, yaw = 0.0, roll = 0.0, fz = 0.0;
  Case c;
};

// ---- reading the cases file ---------------------------------------------------------------

// A non-empty array of numbers `key` of [audit], or `fallback` when absent.
std::vector<double> NumberList(const io::SourceFile& file, const toml::table& audit,
                               const std::string& key, std::vector<double> fallback) {
  const toml::node* node = audit.get(key);
  if (!node) {
    if (fallback.empty()) file.Fail(nullptr, "audit." + key, "missing: give a list of values");
    return fallback;
  }
  const toml::array* array = node->as_array();
  if (!array || array->empty()) file.Fail(node, "audit." + key, "must be a non-empty list");
  std::vector<double> v;
  for (const toml::node& item : *array) v.push_back(io::ReadNumber(file, item, "audit." + key));
  return v;
}

struct Entry {
  std::string name;
  toml::table section;  // the [rail] or [wheel] keys
  toml::table changes;  // of [track] or [wheelset]
};

// The [[audit.rail]] or [[audit.wheel]] entries; each needs a name and a profile that exists.
std::vector<Entry> Entries(const io::SourceFile& file, const toml::table& audit,
                           const std::string& kind, const std::string& changes_key,
                           const fs::path& dir) {
  const std::string path = "audit." + kind;
  const toml::node* node = audit.get(kind);
  const toml::array* array = node ? node->as_array() : nullptr;
  if (!array || array->empty()) {
    file.Fail(node, path,
              "missing: list the profiles as [[" + path + "]] entries with name and profile");
  }
  std::vector<Entry> entries;
  for (std::size_t k = 0; k < array->size(); ++k) {
    const std::string at = path + "[" + std::to_string(k) + "]";
    const toml::table* t = (*array)[k].as_table();
    if (!t) file.Fail(&(*array)[k], at, "must be a table with name and profile");
    Entry e;
    e.section = *t;
    const auto* name = t->get_as<std::string>("name");
    const auto* profile = t->get_as<std::string>("profile");
    if (!name) file.Fail(t->get("name"), at + ".name", "missing or not a string");
    if (!profile) file.Fail(t->get("profile"), at + ".profile", "missing or not a string");
    const fs::path p =
        fs::path(profile->get()).is_absolute() ? fs::path(profile->get()) : dir / profile->get();
    if (!fs::is_regular_file(p))
      file.Fail(profile, at + ".profile", "file not found: " + p.string());
    e.name = name->get();
    e.section.erase("name");
    if (const toml::node* changes = t->get(changes_key)) {
      if (!changes->is_table()) file.Fail(changes, at + "." + changes_key, "must be a table");
      e.changes = *changes->as_table();
      e.section.erase(changes_key);
    }
    entries.push_back(std::move(e));
  }
  return entries;
}

void CheckAuditKeys(const io::SourceFile& file, const toml::table& audit) {
  const std::vector<std::string_view> keys = {"y", "yaw", "roll", "fz", "rail", "wheel"};
  for (const auto& [key, node] : audit) {
    if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
    const std::string suggestion = io::SuggestName(key.str(), keys);
    file.Fail(&node, "audit." + std::string(key.str()),
              "unknown key" + (suggestion.empty() ? "" : " (did you mean " + suggestion + "?)") +
                  "; allowed: y, yaw, roll, fz, [[audit.rail]], [[audit.wheel]]");
  }
}

// `changes` written over the section `name` of `t`.
void Merge(toml::table* t, const std::string& name, const toml::table& changes) {
  if (changes.empty()) return;
  if (!t->get(name)) t->insert(name, toml::table{});
  toml::table* section = t->get_as<toml::table>(name);
  for (const auto& [key, value] : changes) section->insert_or_assign(key, value);
}

// The profile read once per file and options, shared by every case that names it.
class SplineCache {
 public:
  std::shared_ptr<const ProfileSpline> Get(const ProfileSource& s, ProfileKind kind,
                                           const std::string& who) {
    const ProfileOptions options = ProfileOptionsOf(s);
    std::ostringstream key;
    key << s.path.string() << '|' << s.mirror_y << s.mirror_y_auto << static_cast<int>(s.mirror_z)
        << '|' << s.smooth << '|' << s.scale_yz;
    auto& spline = splines_[key.str()];
    if (!spline) {
      try {
        spline = std::make_shared<const ProfileSpline>(ReadProfile(s.path.string(), kind, options));
      } catch (const InputError& e) {
        throw InputError(who + ": " + e.what());
      }
    }
    return spline;
  }

 private:
  std::map<std::string, std::shared_ptr<const ProfileSpline>> splines_;
};

// The case of one wheel on one rail (`pair`: the case file with their sections) in the pose of
// `a`, its profiles read through `splines`.
AuditCase PoseCase(const toml::table& pair, AuditCase a, const fs::path& path,
                   const std::string& who, SplineCache* splines) {
  toml::table t = pair;
  Merge(&t, "state", toml::table{{"y", a.y}, {"yaw", a.yaw}, {"roll", a.roll}, {"fz", a.fz}});
  t.get_as<toml::table>("state")->erase("z");
  std::ostringstream generated;
  generated << t;
  a.c = ParseCase(generated.str(), fs::absolute(path).parent_path(), who);
  if (a.c.type != CaseType::kWheelRail) {
    throw InputError(path.string() + ": problem.type must be \"wheel-rail\"");
  }
  a.c.rail.spline = splines->Get(a.c.rail, ProfileKind::kRail, who);
  a.c.wheel.spline = splines->Get(a.c.wheel, ProfileKind::kWheel, who);
  return a;
}

std::vector<AuditCase> LoadAudit(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot read the cases file");
  std::stringstream text;
  text << in.rdbuf();
  const io::SourceFile file(path.string());
  toml::table root = file.Parse(text.str());
  const toml::table* audit = root.get_as<toml::table>("audit");
  if (!audit) {
    file.Fail(root.get("audit"), "audit",
              "missing: a cases file is a wheel-rail case with an [audit] section (y, yaw, roll, "
              "fz and [[audit.rail]], [[audit.wheel]] entries); see tables/planar_audit.toml");
  }
  CheckAuditKeys(file, *audit);
  const fs::path dir = fs::absolute(path).parent_path();
  const std::vector<double> ys = NumberList(file, *audit, "y", {0.0});
  const std::vector<double> yaws = NumberList(file, *audit, "yaw", {0.0});
  const std::vector<double> rolls = NumberList(file, *audit, "roll", {0.0});
  const std::vector<double> fzs = NumberList(file, *audit, "fz", {});
  const std::vector<Entry> rails = Entries(file, *audit, "rail", "track", dir);
  const std::vector<Entry> wheels = Entries(file, *audit, "wheel", "wheelset", dir);
  const std::size_t count =
      rails.size() * wheels.size() * ys.size() * yaws.size() * rolls.size() * fzs.size();
  if (count > kMaxCases) {
    file.Fail(audit, "audit",
              std::to_string(count) + " cases: at most " + std::to_string(kMaxCases));
  }
  toml::table base = root;
  base.erase("audit");
  SplineCache splines;
  std::vector<AuditCase> cases;
  for (const Entry& wheel : wheels) {
    for (const Entry& rail : rails) {
      toml::table pair = base;
      pair.insert_or_assign("rail", rail.section);
      pair.insert_or_assign("wheel", wheel.section);
      Merge(&pair, "track", rail.changes);
      Merge(&pair, "wheelset", wheel.changes);
      const std::string who =
          path.string() + " (wheel " + wheel.name + " on rail " + rail.name + ")";
      for (double fz : fzs) {
        for (double roll : rolls) {
          for (double yaw : yaws) {
            for (double y : ys) {
              cases.push_back(PoseCase(pair, {wheel.name, rail.name, y, yaw, roll, fz, {}}, path,
                                       who, &splines));
            }
          }
        }
      }
    }
  }
  return cases;
}

// ---- solving and statistics ---------------------------------------------------------------

using Results = std::vector<std::vector<SolveSummary>>;  // [case][method]

Results SolveAudit(const std::vector<AuditCase>& cases, int threads) {
  const std::size_t nm = PaperMethods().size();
  Results r(cases.size(), std::vector<SolveSummary>(nm));
  RunParallel(cases.size() * nm, threads, [&](std::size_t job) {
    const std::size_t k = job / nm, m = job % nm;
    Case c = cases[k].c;
    ApplyPaperMethod(PaperMethods()[m], &c.method);
    r[k][m] = SolveAndSummarize(c);
    r[k][m].result.patches.clear();  // the summary is all that is kept of 2 500 solves
  });
  return r;
}

struct Stats {
  std::size_t n = 0;
  double mean = NAN, mean_abs = NAN, rms = NAN, max_abs = NAN;
};

Stats Statistics(const std::vector<double>& d) {
  Stats s;
  s.n = d.size();
  if (d.empty()) return s;
  double sum = 0.0, sum_abs = 0.0, sum_sq = 0.0, max_abs = 0.0;
  for (double v : d) {
    sum += v;
    sum_abs += std::fabs(v);
    sum_sq += v * v;
    max_abs = std::max(max_abs, std::fabs(v));
  }
  s.mean = sum / d.size();
  s.mean_abs = sum_abs / d.size();
  s.rms = std::sqrt(sum_sq / d.size());
  s.max_abs = max_abs;
  return s;
}

bool Solved(const SolveSummary& s) { return s.status == "ok" && std::isfinite(s.lv); }

// The quantities compared: L/V as is, the forces in % of the case's load.
const std::vector<std::string>& Quantities() {
  static const std::vector<std::string> q = {"lv", "fx", "fy", "fz"};
  return q;
}

double Difference(const std::string& q, const SolveSummary& m, const SolveSummary& ref,
                  double load) {
  if (q == "lv") return m.lv - ref.lv;
  const double a = q == "fx" ? m.fx : q == "fy" ? m.fy : m.fz;
  const double b = q == "fx" ? ref.fx : q == "fy" ? ref.fy : ref.fz;
  return 100.0 * (a - b) / load;
}

// stats[method][quantity] over the cases that both the method and the curved reference solved
// and where the curved reference's |L/V| is at most `lv_limit`.
std::vector<std::vector<Stats>> AllStatistics(const std::vector<AuditCase>& cases, const Results& r,
                                              double lv_limit) {
  std::vector<std::vector<Stats>> stats;
  for (std::size_t m = 0; m < PaperMethods().size(); ++m) {
    std::vector<Stats> per_quantity;
    for (const std::string& q : Quantities()) {
      std::vector<double> d;
      for (std::size_t k = 0; k < cases.size(); ++k) {
        if (Solved(r[k][0]) && Solved(r[k][m]) && std::fabs(r[k][0].lv) <= lv_limit) {
          d.push_back(Difference(q, r[k][m], r[k][0], cases[k].fz));
        }
      }
      per_quantity.push_back(Statistics(d));
    }
    stats.push_back(per_quantity);
  }
  return stats;
}

// The case with the largest |ΔL/V| of any method; cases.size() when none compares.
std::size_t WorstCase(const std::vector<AuditCase>& cases, const Results& r) {
  std::size_t worst = cases.size();
  double largest = -1.0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    for (std::size_t m = 1; m < PaperMethods().size(); ++m) {
      if (!Solved(r[k][0]) || !Solved(r[k][m])) continue;
      const double d = std::fabs(r[k][m].lv - r[k][0].lv);
      if (d > largest) largest = d, worst = k;
    }
  }
  return worst;
}

// ---- output -------------------------------------------------------------------------------

void WriteCasesCsv(const fs::path& dir, const std::vector<AuditCase>& cases, const Results& r) {
  OutputText csv(dir / "planar_cases.csv");
  csv.precision(10);
  csv << "case,wheel,rail,y,yaw,roll,load,method_index,method,status,fx,fy,fz,lv,fs,n_patches,"
         "contact_angle_deg,z,message\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const AuditCase& a = cases[k];
    for (std::size_t m = 0; m < PaperMethods().size(); ++m) {
      const SolveSummary& s = r[k][m];
      std::string message = s.message;
      std::replace(message.begin(), message.end(), '"', '\'');
      csv << k << ',' << a.wheel << ',' << a.rail << ',' << a.y << ',' << a.yaw << ',' << a.roll
          << ',' << a.fz << ',' << m << ',' << PaperMethods()[m].name << ',' << s.status << ','
          << s.fx << ',' << s.fy << ',' << s.fz << ',' << s.lv << ',' << s.fs << ',' << s.n_patches
          << ',' << Degrees(s.contact_angle) << ',' << s.z << ",\"" << message << "\"\n";
    }
  }
  csv.Commit();
}

// The statistics of every case ("all") and of those within the L/V limit ("lv_le_LIMIT").
struct StatsSet {
  std::vector<std::vector<Stats>> all, below;
  double lv_limit = 0.0;
  std::string BelowName() const { return "lv_le_" + FormatNumber(lv_limit); }
};

void WriteStatsCsv(const fs::path& dir, const StatsSet& set) {
  OutputText csv(dir / "planar_stats.csv");
  csv.precision(10);
  csv << "subset,method_index,method,quantity,unit,cases,mean,mean_abs,rms,max_abs\n";
  for (const auto& [subset, stats] :
       {std::pair{std::string("all"), &set.all}, std::pair{set.BelowName(), &set.below}}) {
    for (std::size_t m = 1; m < stats->size(); ++m) {
      for (std::size_t q = 0; q < Quantities().size(); ++q) {
        const Stats& s = (*stats)[m][q];
        csv << subset << ',' << m << ',' << PaperMethods()[m].name << ',' << Quantities()[q] << ','
            << (q == 0 ? "-" : "% of load") << ',' << s.n << ',' << s.mean << ',' << s.mean_abs
            << ',' << s.rms << ',' << s.max_abs << '\n';
      }
    }
  }
  csv.Commit();
}

// Fig. 20: L/V of every case and method, the cases sorted by the curved reference's L/V.
void PlotLv(const fs::path& dir, const std::vector<AuditCase>& cases, const Results& r) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (Solved(r[k][0])) order.push_back(k);
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return r[a][0].lv < r[b][0].lv; });
  OutputText dat(dir / "planar_lv.dat");
  dat << "# rank, case, then L/V of each method of Table 1 (NaN: not solved)\n";
  for (std::size_t i = 0; i < order.size(); ++i) {
    dat << i << ' ' << order[i];
    for (const SolveSummary& s : r[order[i]]) dat << ' ' << (Solved(s) ? s.lv : NAN);
    dat << '\n';
  }
  dat.Commit();
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1100,650 font ',10'\nset output 'planar_lv.png'\n"
     << "set title 'L/V of every case, sorted by the curved reference (paper Fig. 20)'\n"
     << "set xlabel 'case, by the curved L/V'\nset ylabel 'L/V = F_y / F_z, -'\nset grid\n"
     << "set key outside right\nplot ";
  for (std::size_t m = PaperMethods().size(); m-- > 0;) {
    gp << "'planar_lv.dat' using 1:" << m + 3
       << (m == 0 ? " with lines lw 2 lc rgb 'black'" : " with points pt 7 ps 0.5") << " title '"
       << PaperMethods()[m].name << "'" << (m ? ", " : "\n");
  }
  RunGnuplot(dir, "planar_lv", gp.str(), kWho);
}

// The line load Σ pn·dx along each grid row, at the row's lateral track position.
void WriteLineLoads(std::ostream& out, std::size_t m, const SolveSummary& s) {
  for (const PatchResult& p : s.result.patches) {
    for (int j = 0; j < p.grid.ny; ++j) {
      double q = 0.0;
      for (int i = 0; i < p.grid.nx; ++i) q += p.pn[p.grid.index(i, j)] * p.grid.dx;
      out << m << ' ' << LateralTrackY(p, j) << ' ' << q << '\n';
    }
    out << '\n';
  }
}

// Fig. 19: the pressures of the case with the largest difference, per method.
std::vector<SolveSummary> PlotWorst(const fs::path& dir, const AuditCase& worst, int threads) {
  std::vector<Case> cases;
  for (const PaperMethod& m : PaperMethods()) {
    cases.push_back(worst.c);
    ApplyPaperMethod(m, &cases.back().method);
  }
  WheelRailOptions fields;
  fields.keep_fields = true;
  std::vector<SolveSummary> s = SolveAll(cases, threads, fields);
  OutputText dat(dir / "planar_worst.dat");
  dat << "# method, lateral track position y (mm), line load sum(pn dx) (N/mm)\n";
  for (std::size_t m = 0; m < s.size(); ++m) WriteLineLoads(dat, m, s[m]);
  dat.Commit();
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1300,480 font ',10'\nset output 'planar_worst.png'\n"
     << "set multiplot layout 1,3 title '" << GnuplotLiteral(worst.wheel + " on " + worst.rail)
     << ", y = " << worst.y << " mm, yaw = " << worst.yaw
     << " rad: the case with the largest L/V difference (paper Fig. 19)'\n"
     << "set xlabel 'lateral position y, track frame, mm'\nset ylabel 'line load, N/mm'\n"
     << "set grid\nset key top left\n";
  const std::vector<std::vector<std::size_t>> panels = {{0, 1}, {0, 2, 3, 4, 5}, {0, 6, 7, 8}};
  const char* titles[] = {"curved reference", "weighted centre", "initial contact"};
  for (std::size_t p = 0; p < panels.size(); ++p) {
    gp << "set title '" << titles[p] << "'\nplot ";
    for (std::size_t i = 0; i < panels[p].size(); ++i) {
      const std::size_t m = panels[p][i];
      gp << (i ? ", " : "") << "'planar_worst.dat' using ($1==" << m << " ? $2 : 1/0):3 with lines"
         << (m == 0 ? " lw 2 lc rgb 'black'" : "") << " title '" << PaperMethods()[m].name << "'";
    }
    gp << "\n";
  }
  gp << "unset multiplot\n";
  RunGnuplot(dir, "planar_worst", gp.str(), kWho);
  return s;
}

// The paper's Table 3 (L/V differences to the curved reference), by method index.
struct PaperRow {
  const char* mean;
  const char* mean_abs;
  const char* rms;
  const char* max_abs;
};
const PaperRow kPaperTable3[] = {{"", "", "", ""},
                                 {"0.0000", "0.0003", "0.001", "0.013"},
                                 {"0.0061", "0.0088", "0.016", "0.129"},
                                 {"0.0046", "0.0067", "0.012", "0.089"},
                                 {"0.0008", "0.0064", "0.013", "0.155"},
                                 {"0.0003", "0.0051", "0.011", "0.170"},
                                 {"−0.0011 (*)", "0.0126 (*)", "0.028 (*)", "0.247 (*)"},
                                 {"0.0005", "0.0064", "0.013", "0.158"},
                                 {"0.0001", "0.0051", "0.011", "0.178"}};

void WriteLvTable(std::ostream& md, const std::vector<std::vector<Stats>>& stats) {
  md << "| method | tested method | cases | mean | mean abs | rms | max abs | paper: mean | mean "
        "abs | rms | max abs |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t m = 1; m < stats.size(); ++m) {
    const Stats& s = stats[m][0];
    const PaperRow& p = kPaperTable3[m];
    md << "| " << PaperMethods()[m].name << " | " << PaperMethods()[m].description << " | " << s.n
       << " | " << Fixed(s.mean, 4) << " | " << Fixed(s.mean_abs, 4) << " | " << Fixed(s.rms, 3)
       << " | " << Fixed(s.max_abs, 3) << " | " << p.mean << " | " << p.mean_abs << " | " << p.rms
       << " | " << p.max_abs << " |\n";
  }
}

void WriteReadme(const fs::path& dir, const std::string& source,
                 const std::vector<AuditCase>& cases, const Results& r, const StatsSet& set,
                 std::size_t worst, const std::vector<SolveSummary>& worst_solves, double seconds,
                 int threads) {
  std::size_t failed = 0;
  for (const auto& row : r) {
    for (const SolveSummary& s : row) failed += Solved(s) ? 0 : 1;
  }
  OutputText md(dir / "README.md");
  md << "# Planar contact methods against the curved reference\n\n"
     << "Generated by `wrc study planar` on `" << source << "`: " << cases.size()
     << " cases (wheel, rail, pose) × " << PaperMethods().size() << " methods of the paper's "
     << "Table 1 in " << Fixed(seconds, 1) << " s on " << threads << " threads; " << failed
     << " solves did not give a result (listed in planar_cases.csv) and their cases are left out "
        "of the comparison of that method. Data: [planar_cases.csv](planar_cases.csv) (every "
        "solve), [planar_stats.csv](planar_stats.csv) (the statistics below); pictures "
        "[planar_lv.png](planar_lv.png) (Fig. 20), [planar_worst.png](planar_worst.png) "
        "(Fig. 19).\n\n"
     << "## Differences of L/V to the curved reference (Table 3)\n\n"
     << "Per case, L/V = Fy/Fz (track frame, on the rail) of the method less that of the curved "
        "reference; then the mean, the mean of the absolute values, the root mean square and "
        "the largest absolute value over the cases.\n\n";
  WriteLvTable(md, set.all);
  md << "\n(*) the paper leaves out 7 wheels with L/V < −1 for icp-loc; wrc keeps every case.\n\n"
     << "### Without flange climbing\n\nThe same over the cases where the curved reference's "
        "|L/V| is at most "
     << FormatNumber(set.lv_limit)
     << " (`--lv-limit`): tread and flange-root contact, where a vehicle spends its running "
        "time, and where the paper's poses from vehicle simulation lie. Beyond, the flange "
        "climbs and the planar methods are not meant to be used.\n\n";
  WriteLvTable(md, set.below);
  md << "\n"
     << "## Differences of the forces, % of the wheel load\n\n"
     << "| method | Fx mean | Fx mean abs | Fx rms | Fx max abs | Fy mean | Fy mean abs | Fy rms | "
        "Fy max abs | Fz mean | Fz mean abs | Fz rms | Fz max abs |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t m = 1; m < set.all.size(); ++m) {
    md << "| " << PaperMethods()[m].name;
    for (std::size_t q = 1; q < Quantities().size(); ++q) {
      const Stats& s = set.all[m][q];
      md << " | " << Fixed(s.mean, 2) << " | " << Fixed(s.mean_abs, 2) << " | " << Fixed(s.rms, 2)
         << " | " << Fixed(s.max_abs, 2);
    }
    md << " |\n";
  }
  md << "\nFz is prescribed (the wheelset height is solved for it), so its difference is the "
        "solver's tolerance only.\n\n";
  if (worst >= cases.size()) return;
  const AuditCase& w = cases[worst];
  md << "## The case with the largest difference (Table 2, Fig. 19)\n\n"
     << "Wheel " << w.wheel << " on rail " << w.rail << ", y = " << w.y << " mm, yaw = " << w.yaw
     << " rad, roll = " << w.roll << " rad, Fz = " << Kn(w.fz) << " kN (case " << worst
     << " of planar_cases.csv):\n\n"
     << "| method | status | reference angle of the main patch, ° | patches | Fx, kN | Fs, kN | "
        "Fy, kN | L/V |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t m = 0; m < worst_solves.size(); ++m) {
    const SolveSummary& s = worst_solves[m];
    md << "| " << PaperMethods()[m].name << " | " << s.status << " | "
       << Fixed(Degrees(s.contact_angle), 1) << " | " << s.n_patches << " | " << Kn(s.fx) << " | "
       << Kn(s.fs) << " | " << Kn(s.fy) << " | " << Fixed(s.lv, 3) << " |\n";
  }
  md << "\n![the line load of each method](planar_worst.png)\n";
  md.Commit();
}

int RunPlanarStudy(const PlanarOptions& o) {
  const fs::path dir = o.out;
  fs::create_directories(dir);
  fs::path cases_file = o.cases;
  std::string source = o.cases;
  if (cases_file.empty()) {
    // The shipped audit, with its profiles, from the copies compiled into the program.
    std::vector<std::string> names;
    for (const ShippedFile& f : ShippedFiles()) {
      if (f.name == "planar_audit.toml" || f.name.rfind("profiles/", 0) == 0)
        names.emplace_back(f.name);
    }
    cases_file = WriteShippedFiles(dir / "inputs", names).front();
    source = "tables/planar_audit.toml";
  }
  const std::vector<AuditCase> cases = LoadAudit(cases_file);
  std::cerr << kWho << ": " << cases.size() << " cases × " << PaperMethods().size()
            << " methods on " << o.threads << " threads\n";
  const auto t0 = std::chrono::steady_clock::now();
  const Results r = SolveAudit(cases, o.threads);
  const double seconds = SecondsSince(t0);
  const StatsSet stats{AllStatistics(cases, r, INFINITY), AllStatistics(cases, r, o.lv_limit),
                       o.lv_limit};
  WriteCasesCsv(dir, cases, r);
  WriteStatsCsv(dir, stats);
  PlotLv(dir, cases, r);
  const std::size_t worst = WorstCase(cases, r);
  std::vector<SolveSummary> worst_solves;
  if (worst < cases.size()) worst_solves = PlotWorst(dir, cases[worst], o.threads);
  WriteReadme(dir, source, cases, r, stats, worst, worst_solves, seconds, o.threads);
  SayReport(kWho, dir / "README.md");
  return kExitOk;
}

}  // namespace

void AddPlanarStudy(CLI::App& study, int* exit_code) {
  auto* planar = study.add_subcommand(
      "planar",
      "The planar methods of the paper's Table 1 against the curved reference over a set of "
      "profile pairs and poses (Table 3)");
  auto o = std::make_shared<PlanarOptions>();
  AddOutOption(planar, &o->out, "Output directory (CSV, PNG, README.md)");
  planar
      ->add_option("--cases", o->cases,
                   "Cases file (a wheel-rail case with an [audit] section); default: the "
                   "shipped tables/planar_audit.toml")
      ->check(CLI::ExistingFile);
  planar
      ->add_option("--lv-limit", o->lv_limit,
                   "|L/V| of the curved reference up to which a case counts in the statistics "
                   "without flange climbing")
      ->check(ZeroOrMore())
      ->capture_default_str();
  AddThreadsOption(planar, &o->threads, false);
  OnRun(planar, exit_code, kWho, [o]() { return RunPlanarStudy(*o); });
}

}  // namespace wrc::cli
