// radwalk: command-line front end. Parses arguments (CLI11), runs one command, maps errors to exit codes:
//   0 success, 1 a solver did not converge (its status says why), 2 bad input (file, option), 3 numerical
//   failure detected (singular or divergent system), 4 internal error.
// This is the command-line boundary: before any command runs, a parse error is one line naming the unknown
// command, option or value with a "did you mean" (apps/command_line.h) and pointing at the command's own --help;
// output file names are checked against what is written (apps/output_files.h); options the chosen method cannot
// honour are refused (apps/ignored_options.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <set>
#include <string>
#include <thread>
#include <utility>

#include "apps/command_line.h"
#include "apps/ignored_options.h"
#include "apps/options.h"
#include "apps/output_files.h"
#include "apps/pipeline.h"
#include "apps/rank_agreement.h"
#include "core/did_you_mean.h"
#include "formfactor/emitter_form_factors.h"
#include "core/distributed.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/path_length.h"
#include "core/progress.h"
#include "io/run_summary.h"
#include "mesh/material_override.h"
#include "mesh/text_scan.h"
#include "walk/measure_by_method.h"
#include "walk/named_choice.h"

using namespace radwalk;
using namespace radwalk::app;

namespace {

bool g_quiet = false;

// The number of an option value, under the one number rule of every text radwalk reads (mesh/text_scan.h
// parse_number: decimal digits with an optional sign, fraction and exponent; no hex floats, no blanks, no nan or
// inf; a value below the smallest double rounds to 0, one above the largest is out of range), finite and of the
// sign asked for, with a one-line message naming what was given (CLI11's own PositiveNumber reports a non-number
// as out of a 309-digit range). Used as a transform (real options) it rewrites the text to the value parsed, in
// 17 significant digits, which CLI11's strtold-and-round reads back as exactly that double, so the option holds
// the correctly rounded value the scene readers would have read; used as a check (integer options) it only
// refuses, and CLI11 converts the digits.
enum class NumberSign { any, non_negative, positive };
CLI::Validator rule_number(NumberSign sign) {
  const std::string what = sign == NumberSign::positive       ? "a positive number"
                           : sign == NumberSign::non_negative ? "a number >= 0"
                                                              : "a finite number";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const ParsedNumber n = parse_number(text);
        const double v = n.value;
        const bool ok = n.status == NumberStatus::ok && std::isfinite(v) &&
                        (sign == NumberSign::positive ? v > 0 : sign == NumberSign::non_negative ? v >= 0 : true);
        if (!ok)
          return "expected " + what + ", got '" + text + "'" +
                 (n.status == NumberStatus::out_of_range ? " (out of range)" : "");
        char canonical[32];
        std::snprintf(canonical, sizeof canonical, "%.17g", v);
        text = canonical;
        return std::string();
      },
      sign == NumberSign::positive ? "POSITIVE" : sign == NumberSign::non_negative ? "NONNEGATIVE" : "NUMBER");
}
const CLI::Validator kPositive = rule_number(NumberSign::positive), kNonNegative = rule_number(NumberSign::non_negative),
                     kReal = rule_number(NumberSign::any);

// A whole number in [lo, hi] written as digits (no sign, exponent or fraction): CLI11 itself saturates
// `--seed -1` to 2^64 - 1 and lets 2^63 - 1 samples overflow what multiplies them. One line naming the range.
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        std::uint64_t v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        const bool ok = !text.empty() && text[0] != '-' && text[0] != '+' && ec == std::errc() &&
                        end == text.data() + text.size() && v >= lo && v <= hi;
        return ok ? std::string()
                  : "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got '" +
                        text + "'";
      },
      "INT");
}
// Threads: at most kMaxThreads (core/parallel.h).
const CLI::Validator kThreads = whole_number(0, kMaxThreads);
const CLI::Validator kSeed = whole_number(0, ~std::uint64_t{0});
// Samples per patch or pixel: from 2 (a standard error needs two) to 2^32, beyond any run's time and far from overflowing what they multiply.
const CLI::Validator kSamples = whole_number(2, std::uint64_t{1} << 32);  // 2: a variance needs two

// The value of a choice option: one of `choices`, else "unknown value 'x' (did you mean 'y'?)".
CLI::Validator one_of(const std::vector<std::string>& choices) {
  std::string listed;
  for (const std::string& c : choices) listed += (listed.empty() ? "{" : ",") + c;
  return CLI::Validator(
      [choices](std::string& text) -> std::string {
        for (const std::string& c : choices)
          if (text == c) return "";
        return unknown_choice(text, choices);
      },
      listed + "}");
}

// An output file: the extension of what is written there, in an existing directory (apps/output_files.h).
CLI::Validator output_file(OutputFile kind) {
  return CLI::Validator([kind](std::string& path) { return check_output_file(path, kind); },
                        "FILE" + output_extensions(kind));
}

// An input path short enough to open (core/path_length.h): checked before any file is read.
const CLI::Validator kPathFits([](std::string& path) { return path_length_problem(path); }, "PATH");

// The directory of a --progressive series (apps/output_files.h).
const CLI::Validator kSeriesDirectory([](std::string& dir) { return check_series_directory(dir); }, "DIR");

// Every command name and option name the parser knows (for the messages about those it does not).
CommandLineWords words_of(const CLI::App& app) {
  CommandLineWords words;
  const auto names = [](const CLI::App& a) {
    std::vector<std::string> out;
    for (const CLI::Option* o : a.get_options()) {
      for (const std::string& n : o->get_snames()) out.push_back("-" + n);
      for (const std::string& n : o->get_lnames()) out.push_back("--" + n);
    }
    return out;
  };
  words.options[""] = names(app);
  for (const CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; })) {
    words.commands.push_back(cmd->get_name());
    words.options[cmd->get_name()] = names(*cmd);
  }
  return words;
}

// The one-line message of a parse error: the first unknown command or option if there is one (the likely
// cause whatever CLI11 reports, e.g. "A subcommand is required" for a mistyped command), else CLI11's own.
std::string parse_error_message(const CLI::ParseError& e, const std::vector<std::string>& args,
                                const CommandLineWords& words) {
  const std::string unknown = unknown_word(args, words);
  if (!unknown.empty()) return unknown;
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    const std::string::size_type colon = what.find(": ");
    if (colon != std::string::npos) return "unexpected argument '" + what.substr(colon + 2) + "'";
  }
  return what;
}

// Refuses the options `cmd` was given that its method cannot honour (apps/ignored_options.h): one InputError
// naming them all.
template <class Command>
void refuse_inapplicable(const CLI::App* cmd, const Command& command) {
  const OptionGiven given = [cmd](const std::string& name) {
    const CLI::Option* o = cmd->get_option_no_throw(name);
    if (!o) throw InternalError("ignored-options table names " + name + ", which '" + cmd->get_name() + "' lacks");
    return o->count() > 0;
  };
  std::string message;
  for (const std::string& m : ignored_options(command, given)) message += (message.empty() ? "" : "; ") + m;
  if (!message.empty()) throw InputError(message);
}

// --target-error takes the hierarchical route unless --target-route uniform: `hierarchical` is set for the route's
// checks and solve. --hierarchical with --target-route uniform is a contradiction, refused.
void choose_target_route(SolveCommand& c) {
  if (!(c.target_error > 0)) return;
  if (c.target_route == "uniform" && c.hierarchical)
    throw InputError("--hierarchical and --target-route uniform contradict each other: --target-error takes the "
                     "hierarchical route by default (give --hierarchical or neither) or splits the patches "
                     "themselves with --target-route uniform");
  if (c.target_route == "hierarchical") c.hierarchical = true;
}

void add_scene_options(CLI::App* cmd, SceneOptions& o, bool patching = true, bool outputs = true) {
  cmd->add_flag("-q,--quiet", g_quiet,
                "No progress, notes or scene warnings on stderr (the scene's repairs and warnings are counted in "
                "one line and listed in --json; other warnings and errors still print)");
  cmd->add_option("scene", o.scene, "Scene file: OBJ (+MTL), PLY, STL (materials by --set), glTF/GLB, VTK .vtp/.vtk")->required()->check(kPathFits);
  cmd->add_option("--set", o.set_material,
                  "Override a material: MATERIAL.Kd=r,g,b (rho) or MATERIAL.Ke=r,g,b (emitted radiance); one "
                  "value is grey; repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--rho-scale", o.rho_scale, "Multiply every material's Kd by S (after --set); refused if a "
                                              "channel reaches 1")
      ->transform(kNonNegative)
      ->capture_default_str();
  if (patching)
    cmd->add_option("--max-edge", o.max_edge,
                    "Split faces until no patch edge is longer than L (mesh units); 0 keeps input faces. Each face "
                    "is split on its own: a face whose edges are all at most L stays whole")
        ->transform(kNonNegative)
        ->capture_default_str();
  if (patching)
    cmd->add_flag("--two-sided", o.two_sided,
                  "Make every material two-sided: each face becomes a front and a back patch with a B each (per "
                  "material: 'radwalk_two_sided 1' in its MTL block); default one-sided, the back absorbs");
  if (patching)
    cmd->add_option("--max-area", o.max_area,
                    "Split faces until no patch area is above A (mesh units squared; with --max-edge both hold); "
                    "0: no bound")
        ->transform(kNonNegative)
        ->capture_default_str();
  if (patching)
    cmd->add_flag("--contact-cut,!--no-contact-cut", o.contact_cut,
                  "Cut a face that an object stands on along the contact footprint and along the lines other faces "
                  "touch it, so that no patch averages the lit part with the part hidden underneath (on by default; "
                  "made when faces are split: --max-edge, --max-area, --target-error; --no-contact-cut keeps the "
                  "plain split; contacts are always noted)");
  cmd->add_option("--scale", o.scale,
                  "Multiply every coordinate by S before anything else (--unit mm --scale 0.001: metres); lengths, "
                  "areas, --max-edge and B are then in the scaled unit")
      ->transform(kPositive)
      ->capture_default_str();
  cmd->add_option("--unit", o.unit,
                  "The unit of the file's coordinates (mm, cm, m, in, ft): the summaries name lengths and B (W per "
                  "unit^2) in it, or in the unit --scale converts to")
      ->check(CLI::IsMember({"mm", "cm", "m", "in", "ft"}));
  cmd->add_option("--orient", o.orient,
                  "Orientation of the faces by shells: outward (faces agree with their neighbours, closed objects "
                  "face out, the enclosing room in), consistent (agree only, the file's majority), none (as the "
                  "file has them). A .vtp or .obj radwalk wrote keeps the orientation its run gave its patches "
                  "unless --orient is given")
      ->check(CLI::IsMember({"none", "consistent", "outward"}))
      ->each([&o](const std::string&) { o.orient_given = true; })
      ->capture_default_str();
  cmd->add_option("--open-shells", o.open_shells,
                  "Faces of open shells (surfaces that enclose no volume: sheets, bottomless boxes): auto (two-sided "
                  "inside a closed room, where light reaches their backs; one-sided in an open scene), one-sided as "
                  "the file has them, or two-sided (a front and a back patch, so light reaching their backs is not "
                  "lost)")
      ->check(CLI::IsMember({"auto", "one-sided", "two-sided"}))
      ->capture_default_str();
  cmd->add_flag("--strict", o.strict,
                "Refuse what would be repaired (polygons of more than 4 corners, zero-area faces, bent or "
                "non-convex quads) instead of repairing it with a warning");
  cmd->add_option("--threads", o.threads, "Worker threads (0 = all cores)")
      ->check(kThreads)
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Random seed; same seed, same output, whatever the thread count")
      ->check(kSeed)
      ->capture_default_str();
  if (outputs) {
    cmd->add_option("--csv", o.csv, "Write per-patch results as CSV ('-': to standard output, the results' lines "
                                    "then on stderr)")
        ->check(output_file(OutputFile::csv));
    cmd->add_option("--json", o.json, "Write a JSON summary (counts, timings, memory, warnings; '-': to standard "
                                      "output)")
        ->check(output_file(OutputFile::json));
    cmd->add_option("--paraview-state", o.paraview_state,
                    "Write a ParaView state FILE.py that opens the .vtp as a figure: B in Viridis over the non-emitters' range, "
                    "colour bar with unit, smooth, from the one camera rule (README)")
        ->check(kPathFits);
  }
}

void add_form_factor_options(CLI::App* cmd, FormFactorCliOptions& o) {
  auto* rays = cmd->add_option("--rays", o.rays, "Rays per patch for the form factors")
                   ->check(kPositive)
                   ->capture_default_str();
  auto* density = cmd->add_option("--rays-per-area", o.rays_per_area,
                                  "Rays per unit area (at least --min-rays per patch) instead of --rays")
                      ->transform(kPositive);
  rays->excludes(density);
  cmd->add_option("--min-rays", o.min_rays, "Minimum rays per patch with --rays-per-area")
      ->check(kPositive)
      ->capture_default_str();
  auto* file =
      cmd->add_option("--form-factors", o.form_factors,
                      "Read F from a file of 'radwalk formfactors' instead of tracing: FILE.mtx (Matrix Market) or FILE.npz (binary CSR, memory-mapped)")
          ->check(kPathFits)
          ->check(CLI::ExistingFile);
  file->excludes(rays)->excludes(density);
  cmd->add_flag("--normalise-rows", o.normalise_rows,
                "With --form-factors: divide every row that sums above 1 by its sum (a file's rows may exceed 1 by "
                "up to 1e-3, e.g. another program's integration error; without this they are used as read, with a "
                "warning naming the worst)")
      ->needs(file);
  cmd->add_flag("--reciprocity", o.reciprocity,
                "Replace A_i F_ij and A_j F_ji by their mean (reports the change; rows never exceed 1)");
  cmd->add_flag("--enforce-closure", o.enforce_closure,
                "Closed scenes: adjust F by least squares (variance-weighted, non-negative, same pattern) so that "
                "every row sums to 1 and A_i F_ij = A_j F_ji (docs/theory/closure.md); refused when rays escape")
      ->excludes(cmd->get_option("--reciprocity"));
  auto* sobol = cmd->add_flag("--sobol-rays,!--no-sobol-rays", o.sobol_rays,
                "Cosine rays from randomised Sobol points, stratified in origin and direction together (the default); "
                "--no-sobol-rays: jittered strata")
      ->capture_default_str();
  auto* emitter = cmd->add_option("--emitter-columns", o.emitter_samples,
                  "Each F_ie to an emitter e from M shadow samples per patch: the exact point-to-polygon form factor "
                  "corrected for occlusion (exact where unoccluded), replacing the cosine rays' count. auto (the "
                  "default): M = a third of the rays per patch for small lights (emitters on at most 10 % of the "
                  "area, in at most M patches), else none; 0: none")
      ->transform(CLI::Validator(
          [](std::string& text) {
            if (text == "auto") {
              text = std::to_string(kAutoEmitterSamples);
              return std::string();
            }
            try {
              std::size_t used = 0;
              const long m = std::stol(text, &used);
              if (used == text.size() && m >= 0) return std::string();
            } catch (...) {
            }
            return std::string("must be auto or an integer >= 0");
          },
          "auto|M"))
      ->default_str("auto");
  auto* analytic = cmd->add_flag("--analytic", o.analytic,
                "Exact form factors of every pair of patches that face each other (contour integration) times their "
                "visibility: 1 where nothing is between them, 0 where one patch hides them, otherwise estimated by "
                "rays between point pairs; reciprocal, with per-row standard errors (at most 20000 patches without "
                "--analytic-cutoff)");
  auto* samples = cmd->add_option("--visibility-samples", o.visibility_samples,
                  "With --analytic: at most this many point pairs (a power of 2, >= 32) for the visibility of a partly "
                  "hidden pair")
      ->check(CLI::Validator(
          [](std::string& text) {
            long m = 0;
            try {
              m = std::stol(text);
            } catch (...) {
              return std::string("must be a power of 2 in [32, 16777216]");
            }
            return m >= 32 && m <= (1L << 24) && (m & (m - 1)) == 0 ? std::string()
                                                                     : std::string("must be a power of 2 in [32, 16777216]");
          },
          "POWER_OF_2"))
      ->capture_default_str();
  auto* cutoff = cmd->add_option("--analytic-cutoff", o.analytic_cutoff,
                  "With --analytic: drop the pairs of patches whose form factors are both proven at most this "
                  "(from their distance: F_ij <= A_j / (pi d^2)), found by a tree of patches instead of every pair; "
                  "each row's dropped sum is bounded and estimated in the JSON summary. 0 computes every pair (at "
                  "most 20000 patches)")
      ->check(CLI::Range(0.0, 0.999999))
      ->capture_default_str();
  cutoff->needs(analytic);
  cmd->add_option("--analytic-cutoff-rays", o.analytic_cutoff_rays,
                  "With --analytic-cutoff: estimate the dropped pairs by this many cosine rays a patch (their hits on "
                  "dropped pairs, averaged over both directions: reciprocal, unbiased) instead of leaving them out")
      ->check(CLI::Range(1L, 1L << 24))
      ->needs(cutoff);
  samples->needs(analytic);
  analytic->excludes(rays)->excludes(density)->excludes(file)->excludes(sobol)->excludes(emitter);
  analytic->excludes(cmd->get_option("--min-rays"));
}

// Runs f, which converts a name with one of the walk layer's parsers, turning its InputError (the valid names and
// the nearest) into a parse error of `flag`.
template <class F>
void walk_choice(const std::string& flag, F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    throw CLI::ValidationError(flag, e.what());
  }
}

// "a (help of a), b (help of b)" for a table of named choices.
template <class Rows>
std::string walk_choices_help(const Rows& rows) {
  std::string s;
  for (const auto& row : rows)
    s += (s.empty() ? "" : ", ") + std::string(row.name) + " (" + std::string(row.help) + ")";
  return s;
}

// An option whose value is a name from one of the walk layer's tables, converted by that table's parser.
template <class T, class Parse>
void add_walk_choice(CLI::App* cmd, const std::string& flag, T& target, Parse parse, std::string_view current,
                     const std::string& help) {
  cmd->add_option_function<std::string>(
         flag, [&target, parse, flag](const std::string& name) { walk_choice(flag, [&] { target = parse(name); }); },
         help)
      ->default_str(std::string(current));
}

// A former option: refused with a one-line pointer to what replaced it (not in --help).
void add_replaced_option(CLI::App* cmd, const std::string& flag, const std::string& instead) {
  cmd->add_option_function<std::string>(
         flag, [flag, instead](const std::string&) { throw CLI::ValidationError(flag, "no longer exists: " + instead); })
      ->group("");
}

// The command and its option values for the run id (apps/run_metadata.h): one line "NAME=VALUE" per option in
// the order declared, VALUE as given (the values joined by a unit separator) or the default. Left out: what
// does not change what is computed (--threads, --quiet, --help); of the output files only whether each was given.
// Options that do not change what is computed: left out of the run id and free to differ between MPI ranks.
const std::set<std::string> kPerRunIrrelevant = {"--threads", "--quiet", "--help"};
// The output files' options: the run id, and the ranks' agreement, count only whether each was given.
const std::set<std::string> kOutputOptions = {"--output", "--csv",   "--json",       "--vtp",
                                              "--image",  "--paraview-state", "--progressive"};
// The input files' options: the ranks' agreement counts only whether each was given (their bytes are compared
// once read, apps/rank_agreement.h); the run id hashes the names too.
const std::set<std::string> kInputOptions = {"scene", "--form-factors"};

std::string canonical_options(const CLI::App* cmd) {
  std::string canonical = cmd->get_name();
  for (const CLI::Option* o : cmd->get_options()) {
    const std::string name = o->get_name();
    if (kPerRunIrrelevant.count(name)) continue;
    std::string value;
    if (kOutputOptions.count(name)) {
      value = o->count() > 0 ? "given" : "";
    } else if (o->count() > 0) {
      for (const std::string& r : o->results()) value += (value.empty() ? "" : "\x1f") + r;
    } else {
      value = "default:" + o->get_default_str();
    }
    canonical += "\n" + name + "=" + value;
  }
  return canonical;
}

// The command's options as the ranks of an MPI run compare them (apps/rank_agreement.h), in the order declared:
// every option but --threads, --quiet and --help; of the input and output files only whether each was given; of
// flags whether each was given; of the others the values as given (joined by spaces) or the default.
std::vector<OptionSetting> option_settings(const CLI::App* cmd) {
  std::vector<OptionSetting> settings;
  for (const CLI::Option* o : cmd->get_options()) {
    OptionSetting s;
    s.name = o->get_name();
    if (kPerRunIrrelevant.count(s.name)) continue;
    s.given = o->count() > 0;
    if (kOutputOptions.count(s.name) || kInputOptions.count(s.name)) {
      s.kind = OptionSetting::Kind::file;
    } else if (o->get_expected_min() == 0) {  // a flag (CLI11: expects no value)
      s.kind = OptionSetting::Kind::flag;
    } else if (s.given) {
      for (const std::string& r : o->results()) s.value += (s.value.empty() ? "" : " ") + r;
    } else {
      s.value = o->get_default_str();
    }
    settings.push_back(std::move(s));
  }
  return settings;
}

}  // namespace

// The walk method's options of the commands that solve by random walks (solve, exchange): --walk and --estimator
// (their names kept in `cli` until finish_walk_method), the walk counts and the survival rule.
struct WalkMethodCli {
  std::string direction, estimator;
  CLI::Option* walks_per_patch = nullptr;
  CLI::Option* particles = nullptr;
};
void add_walk_method_options(CLI::App* cmd, WalkOptions& walk, WalkMethodCli& cli) {
  cli.direction = direction_name(direction_of(walk.method));
  cli.estimator = method_row(walk.method).estimator;
  cmd->add_option("--walk", cli.direction, "Random walk direction: " + walk_choices_help(kWalkDirections))
      ->capture_default_str();
  cmd->add_option("--estimator", cli.estimator,
                  "Random-walk estimator: gather: " + join_names(estimator_names(WalkDirection::gather)) +
                      "; shoot: " + join_names(estimator_names(WalkDirection::shoot)))
      ->capture_default_str();
  cli.walks_per_patch = cmd->add_option("--walks-per-patch", walk.walks_per_patch,
                                        "Gathering (--walk gather): walks from each estimated patch")
                            ->capture_default_str();
  cli.particles = cmd->add_option("--particles", walk.particles,
                                  "Shooting (--walk shoot): particles in total, for all patches at once")
                      ->capture_default_str();
  add_walk_choice(cmd, "--survival", walk.survival.rule, parse_survival_rule, survival_name(walk.survival.rule),
                  "Random-walk survival probability p_k: " + walk_choices_help(kSurvivalRules));
  cmd->add_option("--survival-constant", walk.survival.constant, "p for --survival constant, in (0, 1)")
      ->transform(kReal)
      ->capture_default_str();
}
// After parsing: the method from --walk and --estimator; when the command solves by walks (`walks`), the walk
// count that the method does not read is refused.
void finish_walk_method(const WalkMethodCli& cli, WalkOptions& walk, bool walks) {
  WalkDirection direction = WalkDirection::gather;
  walk_choice("--walk", [&] { direction = parse_walk_direction(cli.direction); });
  walk_choice("--estimator", [&] { walk.method = walk_method(direction, cli.estimator); });
  if (!walks) return;
  if (is_gathering(walk.method) && cli.particles->count() > 0)
    throw CLI::ValidationError("--particles", "counts shooting particles; gathering walks (--walk gather) take "
                                              "--walks-per-patch");
  if (!is_gathering(walk.method) && cli.walks_per_patch->count() > 0)
    throw CLI::ValidationError("--walks-per-patch", "counts gathering walks; shooting walks (--walk shoot) take "
                                                    "--particles");
}

// The shooting sampler's options (walk_options.h WalkSampler), the same for solve and compare.
void add_sampler_options(CLI::App* cmd, WalkOptions& walk) {
  add_walk_choice(cmd, "--sampler", walk.sampler, parse_walk_sampler, sampler_name(walk.sampler),
                  "Shooting particles: " + walk_choices_help(kWalkSamplers));
  cmd->add_option("--replicates", walk.replicates,
                  "--sampler sobol or jacobi: independent randomisations; the standard errors come from their spread")
      ->capture_default_str();
  cmd->add_flag("--direct-light", walk.direct_light,
                "--sampler sobol or jacobi: the first bounce from the emitters apart (ray kernel: exact point-to-polygon "
                "form factors corrected for occlusion by shadow rays; matrix kernel: exact from F); the particles carry "
                "the indirect light only");
  cmd->add_option("--shadow-rays", walk.shadow_rays,
                  "--direct-light: shadow samples per receiving patch (default particles / (2 x patches))");
}

namespace {
int run_main(int argc, char** argv);
}  // namespace

// Over MPI (mpirun -np R radwalk ...) every rank runs the command; the Session ends the run with one exit code for
// the job (core/distributed.h). A plain run is one process.
int main(int argc, char** argv) {
  distributed::Session session(argc, argv);
  return session.finish(run_main(argc, argv));
}

namespace {
int run_main(int argc, char** argv) {
  CLI::App app{
      "radwalk: solve the radiosity equation B = E + diag(rho) F B on a mesh and compare the solvers.\n"
      "Scene units are the mesh's; Kd = reflectance rho, Ke = emitted radiance, E = pi * Ke (W/m^2).",
      "radwalk"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("radwalk ") + RADWALK_VERSION);
  app.add_flag("-q,--quiet", g_quiet,
               "No progress, notes or scene warnings on stderr (they are counted; other warnings and errors "
               "still print)");
  std::vector<std::string> args(argv, argv + argc);

  SceneOptions check;
  auto* check_cmd = app.add_subcommand("check", "Validate a scene and report what is wrong or was repaired");
  add_scene_options(check_cmd, check, false, false);
  check_cmd->add_option("--json", check.json, "Write the findings as JSON ('-': to standard output)")
      ->check(output_file(OutputFile::json));

  PatchCommand patch;
  auto* patch_cmd = app.add_subcommand("patch", "Validate and split a scene into patches; write them");
  add_scene_options(patch_cmd, patch.scene);
  patch_cmd->add_option("-o,--output", patch.output, "Output: FILE.vtp (ParaView) or FILE.obj (+ .mtl)")
      ->required()
      ->check(output_file(OutputFile::vtp_or_obj));

  FormFactorsCommand ff;
  auto* ff_cmd = app.add_subcommand("formfactors", "Estimate form factors F by cosine-weighted ray shooting");
  add_scene_options(ff_cmd, ff.scene);
  add_form_factor_options(ff_cmd, ff.ff);
  ff_cmd->add_option("-o,--output", ff.mtx, "Write F as FILE.mtx (Matrix Market text, row i = patch i, 1-based) or FILE.npz (binary CSR as scipy.sparse.save_npz, 0-based; fast to read)")
      ->check(output_file(OutputFile::matrix_market));
  ff_cmd->add_option("--vtp", ff.diagnostics_vtp, "Write per-patch diagnostics as .vtp")
      ->check(output_file(OutputFile::vtp));

  SolveCommand solve;
  auto* solve_cmd = app.add_subcommand("solve", "Solve for the radiosity B of every patch");
  add_scene_options(solve_cmd, solve.scene);
  add_form_factor_options(solve_cmd, solve.ff);
  solve_cmd->add_option("-o,--output", solve.scene.vtp, "Write the solution as .vtp (cell field B, point field B)")
      ->check(output_file(OutputFile::vtp));
  solve_cmd
      ->add_option("--solver", solve.solver,
                   "auto (direct where it fits, else gauss-seidel), direct, jacobi, gauss-seidel, southwell, "
                   "gmres, random-walk")
      ->check(one_of({"auto", "direct", "jacobi", "gauss-seidel", "southwell", "gmres", "random-walk"}))
      ->capture_default_str();
  solve_cmd
      ->add_option(
          "--tol", solve.tol,
          "Iterative solvers stop when max over channels of |E - (I - diag(rho) F) B|_inf / |E|_inf <= tol")
      ->transform(kPositive)
      ->capture_default_str();
  solve_cmd
      ->add_option(
          "--max-iterations", solve.max_iterations,
          "Iteration budget: sweeps for jacobi and gauss-seidel (default 10000), shots for southwell "
          "(default 1000 x the patch count)")
      ->check(kPositive);
  // Random walks: the choices and their help come from the walk layer's tables and go through its parsers; counts
  // and ranges are checked by check_walk_options once the scene is loaded.
  WalkMethodCli solve_walk;
  add_walk_method_options(solve_cmd, solve.walk, solve_walk);
  add_walk_choice(solve_cmd, "--kernel", solve.walk.kernel, parse_walk_kernel, kernel_name(solve.walk.kernel),
                  "Transition kernel: " + walk_choices_help(kWalkKernels));
  add_replaced_option(solve_cmd, "--walks",
                      "use --walks-per-patch for gathering walks or --particles for shooting walks");
  solve_cmd->add_option("--patches", solve.walk.patches, "Gathering: estimate only these patches (0-based)");
  solve_cmd->add_flag("--theory", solve.walk.theory,
                      "Also compute the exact per-walk variance (dense; small scenes)");
  solve_cmd->add_flag("--control-variate", solve.walk.control_variate,
                      "Gathering, matrix kernel: walk B - c from the shifted source E - c (1 - rho F 1), c = the "
                      "ambient radiosity sum A E / sum A (1 - rho F 1), and add c back (docs/theory/control_variate.md)");
  add_sampler_options(solve_cmd, solve.walk);
  solve_cmd->callback([&solve, &solve_walk] { finish_walk_method(solve_walk, solve.walk, solve.solver == "random-walk"); });
  solve_cmd
      ->add_option(
          "--refine", solve.refine,
          "Adaptive patching: solve, split every patch whose irradiance (B - E) / rho differs from a "
          "coplanar edge neighbour's by more than TOL (relative), re-solve, repeat")
      ->transform(kPositive);
  solve_cmd->add_option("--refine-steps", solve.refine_steps, "Adaptive patching: at most K refinement steps")
      ->check(kNonNegative)
      ->capture_default_str();
  auto* target = solve_cmd
      ->add_option("--target-error", solve.target_error,
                   "Accuracy on request: solve in steps, adding rays where the statistical error dominates and "
                   "splitting patches where the discretisation error does, until the estimated total error (area-"
                   "weighted RMS relative over the reflecting patches, docs/accuracy.md) is at most E (e.g. 0.01), "
                   "or --max-patches / --max-seconds stop it (exit code 1); by default it splits the leaf elements "
                   "of a tree per input face (--rays: the first step's rays per leaf), see --target-route")
      ->check(CLI::Range(1e-6, 0.999999));
  solve_cmd->add_option("--target-route", solve.target_route,
                        "--target-error: hierarchical (an element tree per input face, its leaves split where the "
                        "estimate says, docs/hierarchy.md) or uniform (the patches themselves split, docs/accuracy.md)")
      ->check(CLI::IsMember({"hierarchical", "uniform"}))
      ->needs(target)
      ->capture_default_str();
  solve_cmd->add_option("--target-each", solve.target_each,
                        "--target-error: also hold the mean radiosity of each material (or object, group) within 0.8 E "
                        "(a margin for its estimate's own error), with its own estimated error (per-patch errors of one "
                        "material are correlated, so its mean can be off by more than E); none: the per-patch RMS only. Default: material, except with "
                        "--hierarchical-transport rays, which cannot hold it (none)")
      ->check(CLI::IsMember({"material", "object", "group", "none"}))
      ->needs(target);
  solve_cmd->add_option("--max-patches", solve.max_patches,
                        "Adaptive patching and --target-error: never split beyond M patches (with --hierarchical: leaves)")
      ->check(kPositive)
      ->capture_default_str();
  solve_cmd->add_option("--max-seconds", solve.max_seconds,
                        "--target-error: start no step that would end after S seconds of the run (0: no limit)")
      ->transform(kNonNegative)
      ->needs(target)
      ->capture_default_str();
  solve_cmd
      ->add_option("--refine-floor", solve.refine_floor,
                   "Adaptive patching: differences are relative to max(H_i, H_j, F x the mean irradiance)")
      ->transform(kNonNegative)
      ->capture_default_str();
  auto* refine_noise = solve_cmd
      ->add_option("--refine-noise", solve.refine_noise,
                   "Adaptive patching: ignore differences within Z form-factor standard errors (0: off)")
      ->transform(kNonNegative)
      ->capture_default_str();
  // The binomial standard errors it needs come from cosine-ray counts, which the analytic route has not.
  solve_cmd->get_option("--analytic")->excludes(refine_noise);
  solve_cmd->add_flag("--hierarchical", solve.hierarchical,
                      "Hierarchical stochastic Jacobi: every patch an element tree refined where a ray's transfer or the "
                      "direct light's fluctuation exceeds --hierarchical-tol x the emitted power; outputs per leaf "
                      "element (docs/hierarchy.md)");
  solve_cmd->add_option("--hierarchical-tol", solve.hierarchical_tol,
                        "Hierarchical: refine while the power an element misplaces exceeds TOL x the emitted power")
      ->transform(kPositive)
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-levels", solve.hierarchical_levels,
                        "Hierarchical: at most L levels of 4-way splits below a patch")
      ->check(CLI::Range(0, 30))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-min-area", solve.hierarchical_min_area,
                        "Hierarchical: no element below this area (mesh units squared; 0: the levels alone)")
      ->transform(kNonNegative)
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-points", solve.hierarchical_points,
                        "Hierarchical: points per element for the direct light and its refinement oracle (a square: "
                        "1, 4, 9, 16, ...)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-rays", solve.hierarchical_rays,
                        "Hierarchical: rays of the indirect shooting, all replicates and iterations together")
      ->check(CLI::Range(1L, 1L << 40))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-replicates", solve.hierarchical_replicates,
                        "Hierarchical: independent replicates for the standard errors (>= 2)")
      ->check(CLI::Range(2, 1 << 16))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-refine", solve.hierarchical_refine,
                        "Hierarchical: what refines the elements: oracle (a-priori oracles, --hierarchical-tol) or "
                        "estimate (solve, estimate each leaf's error, split the largest, repeat; needs "
                        "--hierarchical-target or --hierarchical-max-leaves)")
      ->check(CLI::IsMember({"oracle", "estimate"}))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-transport", solve.hierarchical_transport,
                        "Hierarchical --target-error: how each step solves the leaves: form-factors (the leaves as "
                        "patches, traced F with the emitter columns exact and the direct solve, as the uniform "
                        "route) or rays (hierarchical stochastic Jacobi)")
      ->check(CLI::IsMember({"form-factors", "rays"}))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-split", solve.hierarchical_split,
                        "Hierarchical --target-error: how leaves are split: adaptive (a quad cut into 4 bands across "
                        "its long direction, or across the direction in which its radiosity varies, estimated for the "
                        "leaves to split; else in 4 quarters; docs/hierarchy.md, Band splits) or regular (always 4 "
                        "similar children)")
      ->check(CLI::IsMember({"regular", "adaptive"}))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-clusters", solve.hierarchical_clusters,
                        "Hierarchical: oriented clusters of patches that receive a distant shooter's rays as one and "
                        "spread them over their members by the cosine rule (docs/hierarchy.md, Clusters)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-cluster-ratio", solve.hierarchical_cluster_ratio,
                        "Hierarchical clusters: a cluster receives as one only where its radius is at most this "
                        "fraction of its distance to the shooter")
      ->transform(kPositive)
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-target", solve.hierarchical_target,
                        "Hierarchical, refined by the estimate: stop once the estimated relative L2 error is at most "
                        "this (0: the budget alone)")
      ->transform(kNonNegative)
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-max-leaves", solve.hierarchical_max_leaves,
                        "Hierarchical, refined by the estimate: at most this many leaves (0: no budget)")
      ->check(CLI::Range(0L, 1L << 40))
      ->capture_default_str();
  solve_cmd->add_option("--hierarchical-steps", solve.hierarchical_steps,
                        "Hierarchical, refined by the estimate: at most this many splitting steps")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  solve_cmd
      ->add_option("--discretisation-directions", solve.discretisation_directions,
                   "Directions per point of the discretisation error estimate B_disc (24 L rays per patch; 0: not "
                   "estimated)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  solve_cmd->add_option(
      "--progressive", solve.progressive,
      "Write a series DIR/step_NNNN.vtp + DIR/solve.pvd for ParaView: the iterates of jacobi, gauss-seidel or "
      "southwell (time = iteration, at most 200 steps), or for random-walk the estimate and B_se after 1, 2, 4, "
      "... batches of walks (time = walks; costs about one more run)")
      ->check(kSeriesDirectory);

  ExchangeCommand exchange;
  auto* exchange_cmd = app.add_subcommand(
      "exchange", "Grey diffuse radiative heat exchange (net-radiation method): emissivity and temperature or heat "
                  "flux per material in; J, q, Q, T per patch, the energy balance and group tables out");
  add_scene_options(exchange_cmd, exchange.scene);
  add_form_factor_options(exchange_cmd, exchange.ff);
  exchange_cmd->add_option("-o,--output", exchange.scene.vtp, "Write J, q, Q, T and their errors per patch as .vtp")
      ->check(output_file(OutputFile::vtp));
  exchange_cmd
      ->add_option("--solver", exchange.solver,
                   "auto (direct where it fits, else gmres), direct, jacobi, gauss-seidel, southwell, gmres, "
                   "random-walk (on the matrix kernel; refused where a re-radiating face makes the walks diverge)")
      ->check(one_of({"auto", "direct", "jacobi", "gauss-seidel", "southwell", "gmres", "random-walk"}))
      ->capture_default_str();
  WalkMethodCli exchange_walk;
  add_walk_method_options(exchange_cmd, exchange.walk, exchange_walk);
  exchange_cmd->callback([&exchange, &exchange_walk] {
    finish_walk_method(exchange_walk, exchange.walk, exchange.solver == "random-walk");
  });
  exchange_cmd
      ->add_option("--tol", exchange.tol, "Iterative solvers stop at this relative residual of the radiosity form")
      ->transform(kPositive)
      ->capture_default_str();
  exchange_cmd->add_option("--max-iterations", exchange.max_iterations, "Iteration budget of the iterative solvers")
      ->check(kPositive);
  exchange_cmd
      ->add_option_function<double>(
          "--ambient-temperature",
          [&exchange](double T) {
            exchange.ambient_temperature = T;
            exchange.ambient_given = true;
          },
          "Temperature (K) of the black ambient that escaping radiation reaches (open scenes); default 0 K")
      ->transform(kNonNegative);
  exchange_cmd
      ->add_option("--group-by", exchange.group_by,
                   "What the group tables aggregate: object, group (OBJ o / g, glTF node / mesh) or material")
      ->check(one_of({"object", "group", "material"}))
      ->capture_default_str();
  exchange_cmd
      ->add_option("--contact-faces", exchange.contact_faces,
                   "Patches touching another surface (faces lying on a support, e.g. furniture bottoms on the floor, "
                   "and the support under them; patch/contact.h): include them in the exchange (reported in W) or "
                   "exclude them (their rows and columns of F removed; heat through a contact is conduction; the supports are "
                   "then cut along the footprints, as --contact-cut, when faces are split)")
      ->check(one_of({"include", "exclude"}))
      ->capture_default_str();
  exchange_cmd->add_option("--groups", exchange.groups_csv, "Write Q (W), area, radiant temperature per group as CSV")
      ->check(output_file(OutputFile::csv));
  exchange_cmd
      ->add_option("--group-factors", exchange.group_factors,
                   "Write the view factors between groups as CSV (from, to, F, exchange_area A_from F)")
      ->check(output_file(OutputFile::csv));
  exchange_cmd
      ->add_option("--discretisation-directions", exchange.discretisation_directions,
                   "Directions per point of the discretisation error estimate J_disc (24 L rays per patch; 0: not "
                   "estimated)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  auto* sensitivities = exchange_cmd->add_option(
      "--sensitivities", exchange.sensitivities,
      "dQ_G/d eps_H (W) and dQ_G/d T_H (W/K) for the response groups G named here (comma-separated names of "
      "--group-by, or 'all') and every group H, by one adjoint solve per G (docs/heat-exchange.md)");
  exchange_cmd
      ->add_option("--sensitivities-csv", exchange.sensitivities_csv,
                   "Write the sensitivities as CSV (group_from, group_to, dQ_deps_W, dQ_dT_W_per_K)")
      ->check(output_file(OutputFile::csv))
      ->needs(sensitivities);

  CompareCommand compare;
  auto* compare_cmd =
      app.add_subcommand("compare", "Run random-walk estimators repeatedly; compare their variance and cost");
  add_scene_options(compare_cmd, compare.scene);
  add_form_factor_options(compare_cmd, compare.ff);
  compare_cmd->add_option("-o,--output", compare.scene.vtp, "Write per-patch variances as .vtp")
      ->check(output_file(OutputFile::vtp));
  compare_cmd
      ->add_option_function<std::vector<std::string>>(
          "--estimators",
          [&compare](const std::vector<std::string>& names) {
            walk_choice("--estimators", [&] {
              compare.compare.methods.clear();
              for (const std::string& name : names) compare.compare.methods.push_back(parse_walk_method(name));
            });
          },
          "Comma-separated list from " + join_names(walk_method_names()))
      ->delimiter(',')
      ->default_str("all");
  add_walk_choice(compare_cmd, "--kernel", compare.compare.walk.kernel, parse_walk_kernel,
                  kernel_name(compare.compare.walk.kernel), "Transition kernel: " + walk_choices_help(kWalkKernels));
  compare_cmd
      ->add_option("--walks-per-patch", compare.compare.walk.walks_per_patch,
                   "Budget per run: walks from each patch for gathering methods; shooting methods get the same "
                   "total, walks-per-patch x patches, as particles")
      ->capture_default_str();
  add_replaced_option(compare_cmd, "--walks", "use --walks-per-patch (the budget per patch of every method)");
  compare_cmd->add_option("--runs", compare.compare.runs, "Independent runs per estimator")->capture_default_str();
  add_sampler_options(compare_cmd, compare.compare.walk);

  MeasureCommand measure;
  auto* measure_cmd = app.add_subcommand(
      "measure", "One measurement M = sum_i A_i R_i B_i (a sensor's response) by one method, with its error bar");
  add_scene_options(measure_cmd, measure.scene);
  add_form_factor_options(measure_cmd, measure.ff);
  measure_cmd
      ->add_option("--response", measure.response,
                   "The sensor R: patches:I,J,... | material:NAME | group:NAME (OBJ o/g) | csv:FILE:COLUMN "
                   "(weights by the CSV's patch column) | camera (M = the mean pixel radiance of the view of "
                   "--camera, --width, --height)")
      ->required();
  {
    const std::vector<std::string> methods = measure_method_names();
    measure_cmd
        ->add_option_function<std::string>(
            "--method",
            [&measure, methods](const std::string& name) {
              if (std::find(methods.begin(), methods.end(), name) == methods.end())
                throw CLI::ValidationError("--method", "unknown value '" + name + "'" + did_you_mean(name, methods) +
                                                           "; choose from " + join_names(methods));
              measure.method = name;
            },
            "direct (<R, B> from the direct solve), adjoint-direct (<Y, E> from the adjoint solve), a random-walk "
            "method (" + join_names(walk_method_names()) + ": gathering methods walk from the sensor, shooting "
            "methods from the sources), importance-gather | importance-shoot (importance-driven walks)")
        ->default_str(measure.method);
  }
  add_walk_choice(measure_cmd, "--kernel", measure.walk.kernel, parse_walk_kernel, kernel_name(measure.walk.kernel),
                  "Transition kernel of the walk methods: " + walk_choices_help(kWalkKernels));
  add_walk_choice(measure_cmd, "--survival", measure.walk.survival.rule, parse_survival_rule,
                  survival_name(measure.walk.survival.rule), "Russian roulette: " + walk_choices_help(kSurvivalRules));
  measure_cmd->add_option("--survival-constant", measure.walk.survival.constant, "p for --survival constant, in (0, 1)")
      ->transform(kReal)
      ->capture_default_str();
  measure_cmd->add_option("--walks", measure.walks, "Walks (or particles) in all; per channel for importance walks")
      ->check(CLI::Range(2L, kMaxWalkCount))
      ->capture_default_str();
  measure_cmd
      ->add_option("--importance-sweeps", measure.importance_sweeps,
                   "Importance walks: the importance from K Jacobi sweeps (a cheap approximation); -1 = exact "
                   "(direct solve: zero variance)")
      ->check(CLI::Range(-1, 100000))
      ->capture_default_str();
  measure_cmd
      ->add_option("--defensive", measure.defensive,
                   "Importance walks: fraction alpha of the analog walk mixed in (keeps an approximate importance "
                   "unbiased); default 0 with the exact importance, 0.1 otherwise")
      ->transform(kReal)
      ->check(CLI::Range(0.0, 1.0));
  measure_cmd->add_option("--camera", measure.camera, "With --response camera: px py pz tx ty tz ux uy uz fov_deg")
      ->expected(10)
      ->transform(kReal);
  measure_cmd->add_option("--width", measure.width, "With --response camera: image width")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  measure_cmd->add_option("--height", measure.height, "With --response camera: image height")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  measure_cmd->add_flag("--theory", measure.theory,
                        "Also the exact per-walk variance (matrix kernel, at most 2000 patches)");
  measure_cmd
      ->add_option("--discretisation-directions", measure.discretisation_directions,
                   "Directions per point of M's discretisation error estimate M_disc (24 L rays per patch; 0: not "
                   "estimated)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();

  PathtraceCommand pt;
  auto* pt_cmd = app.add_subcommand("pathtrace", "Continuous path tracer: patch averages and images");
  add_scene_options(pt_cmd, pt.scene);
  pt_cmd->add_option("-o,--output", pt.scene.vtp, "Write patch-average radiosity as .vtp")
      ->check(output_file(OutputFile::vtp));
  pt_cmd->add_option("--spp", pt.spp, "Samples per patch (patch averages) or per pixel (images)")
      ->check(kSamples)
      ->capture_default_str();
  pt_cmd
      ->add_option("--integrator", pt.integrator,
                   "implicit, nee, mis (power heuristic) or light (light tracing)")
      ->check(one_of({"implicit", "nee", "mis", "light"}))
      ->capture_default_str();
  pt_cmd->add_option("--image", pt.image, "Render an image: FILE.png (sRGB) or FILE.exr (linear)")
      ->check(output_file(OutputFile::image));
  pt_cmd->add_option("--width", pt.width, "Image width in pixels")->check(kPositive)->capture_default_str();
  pt_cmd->add_option("--height", pt.height, "Image height in pixels")
      ->check(kPositive)
      ->capture_default_str();
  pt_cmd->add_option("--progressive", pt.progressive,
                     "Write the patch averages after 1, 2, 4, ... batches of samples, with B_se, as "
                     "DIR/step_NNNN.vtp + DIR/pathtrace.pvd (time = samples per patch) for ParaView")
      ->check(kSeriesDirectory);
  pt_cmd
      ->add_option("--camera", pt.camera, "px py pz  tx ty tz  ux uy uz  fov_deg (position, target, up, fov)")
      ->expected(10)
      ->transform(kReal);

  // The command line: parsed, then checked (--paraview-state, distinct files). A refusal (one line) or --help is
  // acted on only once the ranks of an MPI run have agreed on their commands (apps/rank_agreement.h), so that a
  // rank that refuses its command line, or runs another command, never leaves the others waiting.
  std::string refusal;
  std::exception_ptr help_or_version;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      help_or_version = std::current_exception();
    } else {
      const CommandLineWords words = words_of(app);
      refusal = parse_error_message(e, args, words) + "; " + help_pointer(selected_command(args, words));
    }
  }
  Progress::set_enabled(!g_quiet);
  set_quiet(g_quiet);
  for (SceneOptions* o : {&check, &patch.scene, &ff.scene, &solve.scene, &compare.scene, &pt.scene, &measure.scene,
                          &exchange.scene}) {
    o->argv = args;
    report_to_stderr_if_stdout_written(*o);  // --csv - or --json -: stdout carries that output alone
  }
  // --paraview-state: a Python state file, and only beside a .vtp.
  for (const auto& [o, vtp] : {std::pair{&patch.scene, patch.output}, std::pair{&ff.scene, ff.diagnostics_vtp},
                               std::pair{&solve.scene, solve.scene.vtp}, std::pair{&compare.scene, compare.scene.vtp},
                               std::pair{&exchange.scene, exchange.scene.vtp},
                               std::pair{&pt.scene, pt.scene.vtp}}) {
    if (!refusal.empty() || help_or_version || o->paraview_state.empty()) continue;
    const bool py = o->paraview_state.size() > 3 && o->paraview_state.rfind(".py") == o->paraview_state.size() - 3;
    const bool has_vtp = vtp.size() > 4 && vtp.rfind(".vtp") == vtp.size() - 4;
    if (!py)
      refusal = o->paraview_state + ": radwalk writes ParaView's Python state files: name it FILE.py (File > Load "
                                    "State opens it)";
    else if (!has_vtp)
      refusal = "--paraview-state needs a .vtp output (-o FILE.vtp, or --vtp for formfactors)";
  }

  // Every file the command writes; none may be an input or another output (distinct_files.h). The scene's
  // material libraries are known only once it is read: load_validated_mesh checks them.
  if (refusal.empty() && !help_or_version) {
    auto outputs = [](std::initializer_list<std::pair<const char*, std::string>> named) {
      std::vector<NamedFile> files;
      for (const auto& [role, path] : named)
        for (NamedFile& f : output_files_of(role, path)) files.push_back(std::move(f));
      return files;
    };
    check.outputs = outputs({{"--json", check.json}});
    patch.scene.outputs = outputs({{"-o", patch.output}, {"--csv", patch.scene.csv}, {"--json", patch.scene.json},
                                   {"--paraview-state", patch.scene.paraview_state}});
    ff.scene.outputs = outputs({{"-o", ff.mtx}, {"--vtp", ff.diagnostics_vtp}, {"--csv", ff.scene.csv},
                                {"--json", ff.scene.json}, {"--paraview-state", ff.scene.paraview_state}});
    for (SceneOptions* o : {&solve.scene, &compare.scene, &pt.scene, &measure.scene})
      o->outputs = outputs({{"-o", o->vtp}, {"--csv", o->csv}, {"--json", o->json},
                            {"--paraview-state", o->paraview_state}});
    for (NamedFile& f : outputs({{"--image", pt.image}})) pt.scene.outputs.push_back(std::move(f));
    exchange.scene.outputs = outputs({{"-o", exchange.scene.vtp}, {"--csv", exchange.scene.csv},
                                      {"--json", exchange.scene.json}, {"--paraview-state", exchange.scene.paraview_state},
                                      {"--groups", exchange.groups_csv}, {"--group-factors", exchange.group_factors},
                                      {"--sensitivities-csv", exchange.sensitivities_csv}});
    const std::vector<std::pair<SceneOptions*, std::string>> commands = {
        {&check, ""}, {&patch.scene, ""}, {&ff.scene, ff.ff.form_factors}, {&solve.scene, solve.ff.form_factors},
        {&compare.scene, compare.ff.form_factors}, {&pt.scene, ""}, {&measure.scene, measure.ff.form_factors},
        {&exchange.scene, exchange.ff.form_factors}};
    for (const auto& [o, form_factors] : commands) {
      o->form_factors_input = form_factors;
      const std::string clash =
          check_distinct_files(o->outputs, {{"the scene", o->scene}, {"--form-factors", form_factors}});
      if (!clash.empty() && refusal.empty()) refusal = clash;
    }
  }

  RankCommand mine;
  mine.program = std::string("radwalk ") + RADWALK_VERSION + " (" + git_describe() + ")";
  mine.refusal = refusal;
  if (help_or_version) {
    try {
      std::rethrow_exception(help_or_version);
    } catch (const CLI::CallForVersion&) {
      mine.command = "--version";
    } catch (const CLI::ParseError&) {
      mine.command = "--help";
    }
  }
  for (const auto& [o, cmd] : {std::pair{&check, check_cmd}, std::pair{&patch.scene, patch_cmd},
                               std::pair{&ff.scene, ff_cmd}, std::pair{&solve.scene, solve_cmd},
                               std::pair{&compare.scene, compare_cmd}, std::pair{&pt.scene, pt_cmd},
                               std::pair{&measure.scene, measure_cmd}, std::pair{&exchange.scene, exchange_cmd}})
    if (refusal.empty() && !help_or_version && *cmd) {
      o->run_options = canonical_options(cmd);
      mine.command = cmd->get_name();
      mine.options = option_settings(cmd);
    }
  // Over MPI, before any other collective: every rank runs the same command with the same options.
  try {
    agree_on_command(mine);
  } catch (const InputError& e) {
    std::fprintf(stderr, "radwalk: error: %s\n", e.what());
    return 2;
  }
  if (help_or_version) {
    try {
      std::rethrow_exception(help_or_version);
    } catch (const CLI::ParseError& e) {
      return app.exit(e);
    }
  }
  if (!refusal.empty()) {
    std::fprintf(stderr, "radwalk: error: %s\n", refusal.c_str());
    return 2;
  }

  try {
    if (*ff_cmd) refuse_inapplicable(ff_cmd, ff);
    if (*solve_cmd) {
      choose_target_route(solve);
      refuse_inapplicable(solve_cmd, solve);
    }
    if (*compare_cmd) refuse_inapplicable(compare_cmd, compare);
    if (*pt_cmd) refuse_inapplicable(pt_cmd, pt);
    if (*measure_cmd) refuse_inapplicable(measure_cmd, measure);
    if (*exchange_cmd) refuse_inapplicable(exchange_cmd, exchange);
    // The heat-exchange properties of --set are read by radwalk exchange alone.
    for (const auto& [o, cmd] : {std::pair{&patch.scene, patch_cmd}, std::pair{&ff.scene, ff_cmd},
                                 std::pair{&solve.scene, solve_cmd}, std::pair{&compare.scene, compare_cmd},
                                 std::pair{&pt.scene, pt_cmd}, std::pair{&measure.scene, measure_cmd}})
      if (*cmd)
        for (const std::string& text : o->set_material) {
          const MaterialOverride parsed = parse_material_override(text);
          if (is_thermal_property(parsed.property))
            throw InputError("--set '" + text + "': " + parsed.property + " is read by 'radwalk exchange' only; '" +
                             cmd->get_name() + "' would ignore it: remove it");
        }

    // --quiet: the count of the scene warnings it did not print (they are in --json).
    auto counted = [](int code) {
      if (silenced_warnings() > 0)
        std::fprintf(stderr, "radwalk: %ld warning(s) not shown (--quiet)\n", silenced_warnings());
      return code;
    };
    if (*check_cmd) return counted(run_check(check));
    if (*patch_cmd) return counted(run_patch(patch));
    if (*ff_cmd) return counted(run_formfactors(ff));
    if (*solve_cmd) return counted(run_solve(solve));
    if (*compare_cmd) return counted(run_compare(compare));
    if (*pt_cmd) return counted(run_pathtrace(pt));
    if (*measure_cmd) return counted(run_measure(measure));
    if (*exchange_cmd) return counted(run_exchange(exchange));
  } catch (const InputError& e) {
    std::fprintf(stderr, "radwalk: error: %s\n", e.what());
    return 2;
  } catch (const NumericalError& e) {
    std::fprintf(stderr, "radwalk: numerical error: %s\n", e.what());
    return 3;
  } catch (const InternalError& e) {  // a failed RADWALK_CHECK: a bug in radwalk
    std::fprintf(stderr, "radwalk: internal error: %s\n", e.what());
    return 4;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "radwalk: out of memory (try fewer patches: a larger --max-edge)\n");
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "radwalk: internal error: %s\n", e.what());
    return 4;
  }
  return 0;
}
}  // namespace
