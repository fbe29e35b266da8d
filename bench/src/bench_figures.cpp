#include "phedra/bench_figures.h"

#include "phedra/assembly_check.h"
#include "phedra/bench_cases.h"
#include "phedra/cache_sizes.h"
#include "phedra/cut_sheets.h"
#include "phedra/gltf_export.h"
#include "phedra/interval_check.h"
#include "phedra/number_format.h"
#include "phedra/phedron.h"
#include "phedra/repair.h"
#include "phedra/optimize.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/design_preset.h"
#include "phedra/files.h"
#include "phedra/preset.h"
#include "phedra/json_fields.h"
#include "phedra/energy_landscape.h"
#include "phedra/mechanics_figures.h"
#include "phedra/modes_over_interval.h"
#include "phedra/stiffness_modes.h"
#include "phedra/tube.h"

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <thread>

namespace phedra::bench {
namespace {

using Clock = std::chrono::steady_clock;

/// The fastest of repeated runs of `work` (seconds): at least `min_runs`, and
/// until `min_total` seconds have been spent (at most `max_runs`).
template <class Work>
double best_seconds(Work&& work, double min_total = 0.3, int min_runs = 3, int max_runs = 100000) {
  double best = INFINITY, total = 0.0;
  for (int run = 0; run < max_runs && (run < min_runs || total < min_total); ++run) {
    const auto start = Clock::now();
    work();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    best = std::min(best, seconds);
    total += seconds;
  }
  return best;
}

/// Keeps the optimiser from dropping a result.
void keep(const void* p) { asm volatile("" : : "g"(p) : "memory"); }

int exponent(std::size_t n) {
  int e = 0;
  for (std::size_t k = n; k >= 10 && k % 10 == 0; k /= 10) ++e;
  return e;
}
/// "1e6": for figure ids.
std::string power_of_ten(std::size_t n) { return "1e" + std::to_string(exponent(n)); }
/// "10^6": for descriptions.
std::string ten_to(std::size_t n) { return "10^" + std::to_string(exponent(n)); }

std::string machine_name() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpu, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads (benchmarks use one; the energy landscape and large collision sweeps two, as the commands do)";
}

/// /proc/self/status field in KiB (-1 when absent).
long status_kib(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::size_t length = std::strlen(field);
  while (std::getline(status, line)) {
    if (line.compare(0, length, field) == 0 && line.size() > length && line[length] == ':') {
      return std::stol(line.substr(length + 1));
    }
  }
  return -1;
}

/// Peak resident memory (bytes) added while `work` runs, measured in a child
/// process (Linux: /proc/self/clear_refs resets the peak). Negative when it
/// cannot be measured.
template <class Work>
double peak_bytes_in_child(Work&& work) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return -1.0;
  const pid_t child = fork();
  if (child < 0) return -1.0;
  if (child == 0) {
    close(pipe_ends[0]);
    double result = -1.0;
    // Memory the parent freed but kept would be reused here without showing in
    // the resident set: hand it back first.
    malloc_trim(0);
    {
      std::ofstream reset("/proc/self/clear_refs");
      reset << "5";
    }
    const long before = status_kib("VmRSS");
    const long reset_peak = status_kib("VmHWM");
    if (before > 0 && reset_peak <= before + 1024) {  // the reset worked (within 1 MiB)
      work();
      result = 1024.0 * static_cast<double>(status_kib("VmHWM") - before);
    }
    [[maybe_unused]] const auto written = write(pipe_ends[1], &result, sizeof result);
    _exit(0);
  }
  close(pipe_ends[1]);
  double result = -1.0;
  if (read(pipe_ends[0], &result, sizeof result) != sizeof result) result = -1.0;
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return result;
}

/// Seconds of evaluate(t) at 3/10 of the interval, and of writing the same
/// buffer (the memory-bandwidth reference), measured one after the other.
std::pair<double, double> evaluate_and_write_seconds(const PHedron& p) {
  Points out(p.vertex_count());
  const double t = p.t_at_fraction(0.3);
  const double evaluate_s = best_seconds([&] {
    p.evaluate(t, out);
    keep(out.data());
  });
  double x = 0.0;
  const double write_s = best_seconds([&] {
    x += 1.0;
    for (Vec3& v : out) v = Vec3(x, x, x);
    keep(out.data());
  });
  return {evaluate_s, write_s};
}

/// evaluate(t) over writing its buffer, from interleaved repetitions: each
/// repetition times evaluate and then the write (each the fastest of a burst of
/// at least 3 runs and 20 ms), and takes their ratio, so that a neighbour's load
/// falls on both; the median of the ratios is the figure, the lowest and highest
/// its spread.
struct RatioSpread {
  double median = 0.0, lowest = 0.0, highest = 0.0;
  int repetitions = 0;
  std::string text() const {
    return "median of " + std::to_string(repetitions) + " interleaved repetitions, spread " +
           format_significant(lowest, 3) + " to " + format_significant(highest, 3);
  }
};

RatioSpread interleaved_ratio(const PHedron& p, int repetitions) {
  Points out(p.vertex_count());
  const double t = p.t_at_fraction(0.3);
  double x = 0.0;
  std::vector<double> ratios;
  for (int k = 0; k < repetitions; ++k) {
    const double evaluate_s = best_seconds([&] {
      p.evaluate(t, out);
      keep(out.data());
    }, 0.02);
    const double write_s = best_seconds([&] {
      x += 1.0;
      for (Vec3& v : out) v = Vec3(x, x, x);
      keep(out.data());
    }, 0.02);
    ratios.push_back(evaluate_s / write_s);
  }
  std::sort(ratios.begin(), ratios.end());
  const std::size_t n = ratios.size();
  return {n % 2 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]), ratios.front(), ratios.back(),
          repetitions};
}

/// Bytes of a GLB file and the sum of its accessors' data (count x element size).
struct GlbSizes {
  double file = 0.0, payload = 0.0;
};

GlbSizes glb_sizes(const std::string& glb) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  const nlohmann::json json = nlohmann::json::parse(glb.substr(20, u32(12)));
  GlbSizes sizes{static_cast<double>(glb.size()), 0.0};
  for (const auto& a : json["accessors"]) {
    const int component = a["componentType"] == 5126 || a["componentType"] == 5125 ? 4 : 2;
    const std::string type = a["type"];
    const int components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
    sizes.payload += static_cast<double>(a["count"].get<std::size_t>() * component * components);
  }
  return sizes;
}

class Runner {
 public:
  Runner(const BenchOptions& options, const std::function<void(const std::string&)>& progress)
      : options_(options), progress_(progress) {}

  BenchReport run() {
    report_.quick = options_.quick;
    report_.machine = machine_name();
    auto wanted = [&](const std::string& group) {
      return options_.only.empty() || std::find(options_.only.begin(), options_.only.end(), group) != options_.only.end();
    };
    if (wanted("memory")) memory_figure();  // first, while the heap is small
    if (wanted("evaluate")) evaluate_figures();
    if (wanted("accuracy")) accuracy_figures();
    if (wanted("interval")) interval_figures();
    if (wanted("closure")) closure_figure();
    if (wanted("gltf")) gltf_figures();
    if (wanted("repair")) repair_figures();
    if (wanted("optimize")) optimize_figures();
    if (wanted("mechanics")) mechanics_figures();
    return report_;
  }

 private:
  void announce(const std::string& what) {
    if (progress_) progress_(what);
  }
  void add(std::string id, std::string description, double value, std::string unit,
           std::optional<double> target = std::nullopt) {
    report_.figures.push_back({std::move(id), std::move(description), value, std::move(unit), target});
  }

  void evaluate_figures() {
    std::vector<std::size_t> sizes;
    const std::size_t largest = options_.quick ? 100000 : options_.max_vertices;
    for (std::size_t n = 1000; n <= largest; n *= 10) sizes.push_back(n);
    std::vector<double> evaluate_ns, write_ns;
    for (std::size_t n : sizes) {
      announce("evaluate(t), " + std::to_string(n) + " vertices");
      const PHedron p(open_input_with_vertices(n));
      const double vertices = static_cast<double>(p.vertex_count());
      const auto [evaluate_s, write_s] = evaluate_and_write_seconds(p);
      evaluate_ns.push_back(1e9 * evaluate_s / vertices);
      write_ns.push_back(1e9 * write_s / vertices);
      const std::string e = power_of_ten(n);
      add("evaluate.ns_per_vertex_" + e,
          "evaluate(t) of a general open P-hedron, " + std::to_string(p.vertex_count()) + " vertices (" +
              std::to_string(p.topology().rows()) + " profiles)",
          evaluate_ns.back(), "ns/vertex");
      add("write.ns_per_vertex_" + e, "writing the same 24-byte-a-vertex buffer (memory-bandwidth reference)",
          write_ns.back(), "ns/vertex");
      add("write.bandwidth_" + e, "write bandwidth of that buffer", 24.0 / write_ns.back(), "GB/s");
      if (n == 1000000) {
        // Information only: whether 24 MB fit in the last-level cache depends on the machine.
        add("evaluate.ratio_to_write_1e6", "evaluate(t) / buffer write, 10^6 vertices (information: in or beyond the "
                                           "cache by machine; the two figures below are sized by the cache)",
            evaluate_s / write_s, "x");
      }
    }
    cache_figures();
    if (sizes.size() >= 3) {
      // Linear growth: once the buffers no longer fit in the caches (from 10^6
      // vertices on, 64 bytes a vertex), ns per vertex should stay the same.
      const std::size_t from = std::min<std::size_t>(3, sizes.size() - 2);
      add("evaluate.linearity", "ns per vertex of evaluate(t) at " + ten_to(sizes.back()) + " / at " +
                                    ten_to(sizes[from]) + " vertices (1: time exactly linear in the vertex count)",
          evaluate_ns.back() / evaluate_ns[from], "x", 1.5);
      if (sizes.back() != 1000000) {
        add("evaluate.ratio_to_write_" + power_of_ten(sizes.back()),
            "evaluate(t) / buffer write, " + ten_to(sizes.back()) + " vertices", evaluate_ns.back() / write_ns.back(),
            "x");
      }
    }
  }

  /// evaluate(t) against writing its buffer, at sizes chosen by this machine's
  /// caches (sysfs): a buffer at most a quarter of the level-2 cache (both run
  /// from the cache: what the loop itself costs) and one at least four times the
  /// last-level cache (both run from memory: whether evaluate keeps up with it).
  void cache_figures() {
    const CacheSizes caches = read_cache_sizes();
    const std::string where = caches.measured ? "" : " (cache sizes not readable here: 1 MiB and 32 MiB assumed)";
    const int repetitions = options_.quick ? 3 : 15;
    auto ratio = [&](std::size_t vertices, bool mixed) {
      const PHedron p(open_input_with_vertices(vertices, mixed));
      return std::pair{interleaved_ratio(p, repetitions), p.vertex_count()};
    };
    {
      const std::size_t n = std::max<std::size_t>(1000, caches.l2 / 4 / 24);
      announce("evaluate(t) in the level-2 cache, " + std::to_string(n) + " vertices");
      const auto [r, count] = ratio(n, false);
      // The target from what the loop moves (docs/performance.md): a row read (24 bytes a vertex) and
      // its coefficient (8), a row written (24), against the reference's 24 written: 56 / 24 = 2.33.
      add("evaluate.ratio_to_write_in_cache",
          "evaluate(t) / buffer write, " + std::to_string(count) + " vertices: a buffer of at most 1/4 of the level-2 "
              "cache (" + std::to_string(caches.l2 >> 10) + " KiB)" + where + "; " + r.text(),
          r.median, "x", options_.quick ? std::nullopt : std::optional<double>(2.5));
    }
    if (options_.quick) return;
    const std::size_t n = 4 * caches.last_level / 24 + 1;
    for (const bool mixed : {false, true}) {
      announce(std::string("evaluate(t) beyond the last-level cache") + (mixed ? ", mixed signs, " : ", ") +
               std::to_string(n) + " vertices");
      const auto [r, count] = ratio(n, mixed);
      add(std::string("evaluate.ratio_to_write_beyond_cache") + (mixed ? "_mixed_signs" : ""),
          "evaluate(t) / buffer write, " + std::to_string(count) + " vertices" +
              (mixed ? ", every third sign '-' (its ratios per vertex: 8 more bytes to read)" : "") +
              ": a buffer of at least 4 times the last-level cache (" + std::to_string(caches.last_level >> 20) +
              " MiB)" + where + "; " + r.text(),
          r.median, "x", mixed ? 3.0 : 1.3);
    }
  }

  void memory_figure() {
    const std::size_t n = options_.quick ? 100000 : 1000000;
    announce("peak memory, " + std::to_string(n) + " vertices");
    const ControlPolylines input = open_input_with_vertices(n);
    std::size_t vertices = 0;
    {
      const PHedron p(input);
      vertices = p.vertex_count();
    }
    const double peak = peak_bytes_in_child([&] {
      const PHedron p(input);
      Points out(p.vertex_count());
      p.evaluate(p.t_at_fraction(0.3), out);
      keep(out.data());
    });
    if (peak < 0.0) return;  // not measurable here (no /proc/self/clear_refs)
    add("memory.peak_ratio_" + power_of_ten(n),
        "peak resident memory of constructing the P-hedron and evaluating it once, over its vertex buffer (" +
            std::to_string(vertices) + " x 24 bytes)",
        peak / (24.0 * static_cast<double>(vertices)), "x", 3.0);
  }

  void accuracy(const std::string& id, const std::string& what, const ControlPolylines& input) {
    announce("accuracy, " + what);
    const PHedron p(input);
    CheckOptions check;
    check.samples = 5;
    const IntervalCheckReport r = check_over_interval(p, check);
    add("accuracy.planarity_" + id, "planarity error over 5 samples of the interval / model size, " + what,
        r.planarity.value / r.model_size, "relative", 1e-9);
    add("accuracy.isometry_" + id, "isometry error over 5 samples of the interval / model size, " + what,
        r.isometry.value / r.model_size, "relative", 1e-9);
  }

  void accuracy_figures() {
    const std::size_t n = options_.quick ? 100000 : 1000000;
    accuracy(power_of_ten(n), std::to_string(n) + " vertices", open_input_with_vertices(n));
    const std::size_t k = options_.quick ? 1000 : 10000;
    accuracy("profiles_" + power_of_ten(k), std::to_string(k) + " profiles (m = " + std::to_string(k - 1) + "), n = 4",
             general_open_input(k, 4));
    accuracy("n_" + power_of_ten(k), "n = " + std::to_string(k) + " vertices a profile, 100 profiles",
             general_open_input(100, k));
  }

  void interval_figures() {
    const std::size_t profiles = options_.quick ? 1000 : 10000;
    announce("flexion interval, " + std::to_string(profiles) + " profiles");
    const ControlPolylines input = general_open_input(profiles, 4);
    const double construct_s = best_seconds([&] {
      const PHedron p(input);
      keep(&p);
    });
    const PHedron p(input);
    const double search_s = best_seconds([&] {
      const FlexionInterval interval = p.search_flexion_interval();
      keep(&interval);
    });
    const std::string e = power_of_ten(profiles);
    add("interval.ms_" + e, "flexion interval search of a P-hedron with " + std::to_string(profiles) + " profiles",
        1e3 * search_s, "ms", 10.0);
    add("construction.ms_" + e, "whole construction of that P-hedron (nets, motion constants, interval)",
        1e3 * construct_s, "ms");
  }

  void closure_figure() {
    const std::size_t cells = options_.quick ? 3 : 10, segments = options_.quick ? 10 : 100;
    const std::size_t samples = options_.quick ? 100 : 1000;
    announce("closure check, " + std::to_string(cells) + " x " + std::to_string(cells) + " array");
    const Design design = parallelogram_array(cells, segments);
    const std::string what = std::to_string(cells) + " x " + std::to_string(cells) + " parallelogram array, " +
                             std::to_string(segments) + " trajectory segments, " + std::to_string(samples) + " samples";
    for (const bool shape : {false, true}) {
      CheckOptions check;
      check.samples = samples;
      check.shape = shape;
      AssemblyCheckReport report;
      const double seconds = best_seconds([&] { report = check_assembly(design.assembly, check); }, 0.0, 3, 3);
      if (!shape) {
        add("closure_check.s", "closure check (phedra check --closure-only: closure gaps, shared vertices) of a " + what,
            seconds, "s", 1.0);
        add("closure_check.worst_gap", "its worst closure gap / model size (the check " +
                                           std::string(report.passed() ? "passed" : "FAILED") + ")",
            report.closure.value / report.model_size, "relative", 1e-9);
      } else {
        add("full_check.s", "full check (phedra check: also planarity and isometry of every panel) of the same array",
            seconds, "s");
      }
    }
  }

  void gltf_figures() {
    const std::size_t panels = options_.quick ? 1000 : 10000, keyframes = options_.quick ? 50 : 200;
    announce("glTF export, " + std::to_string(panels) + " panels");
    const Design design = open_design_with_panels(panels);
    GltfOptions options;
    options.keyframes.relative_tolerance = 1e9;  // exactly `initial` keyframes
    options.keyframes.initial = keyframes;
    options.keyframes.maximum = keyframes;
    for (const bool morph : {false, true}) {
      options.morph = morph;
      std::string glb;
      GltfReport report;
      const double seconds = best_seconds([&] { glb = gltf_bytes(design, options, &report); }, 0.0, 3, 3);
      const GlbSizes sizes = glb_sizes(glb);
      const std::string what = std::to_string(report.panels) + " panels, " + std::to_string(report.keyframes) +
                               (morph ? " morph targets" : " keyframes");
      const std::string kind = morph ? "morph" : "nodes";
      add("gltf." + kind + "_s",
          std::string("animated glTF export (GLB, ") + (morph ? "default: one mesh, a target a keyframe" : "--nodes: a node a panel") +
              "), " + what,
          // The 2 s target is the default's (morph targets, issue 15). --nodes also
          // measures the vertex error of 10^4 composed panel poses at 15 points of
          // each of the 200 intervals: for small models, no target.
          seconds, "s", morph ? std::optional<double>(2.0) : std::nullopt);
      // The 1.1 target holds for the morph representation; a node a panel costs
      // about 0.55 KB of JSON a panel (node, mesh, two accessors, channel,
      // sampler), so its ratio approaches 1 only as keyframes grow.
      add("gltf." + kind + "_size_ratio", "GLB file size / raw accessor data (geometry and animation), " + what,
          sizes.file / sizes.payload, "x", morph ? std::optional<double>(1.1) : std::nullopt);
      add("gltf." + kind + "_megabytes", "GLB file size, " + what, sizes.file / 1e6, "MB");
    }
    // The default export of an array as users run it: keyframes chosen by the
    // tolerance (the vertex error measured at 15 points between keyframes).
    const std::size_t cells = options_.quick ? 3 : 10;
    const Design array = parallelogram_array(cells, 45);
    GltfReport report;
    const double seconds = best_seconds([&] { gltf_bytes(array, GltfOptions{}, &report); }, 0.0, 2, 2);
    add("gltf.array_default_s",
        "default glTF export (morph targets, keyframes by the 1e-3 tolerance) of a " + std::to_string(cells) + " x " +
            std::to_string(cells) + " array, " + std::to_string(report.panels) + " panels, " +
            std::to_string(report.keyframes) + " keyframes",
        seconds, "s", 2.0);
    // Cut sheets of the same array (phedra outlines: unfolding, labels, pages), no target.
    CutSheets sheets;
    const double outline_seconds = best_seconds([&] { sheets = cut_sheets(array, {}); }, 0.0, 1, 1);
    add("outlines.array_s",
        "cut sheets (outlines: strips unfolded, labels fitted, A4 pages) of the same array, " +
            std::to_string(sheets.pages.size()) + " pages, " + std::to_string(sheets.pieces.size()) + " pieces",
        outline_seconds, "s");
  }

  void repair_one(const std::string& id, const std::string& what, const nlohmann::json& preset,
                  std::optional<double> target) {
    announce("repair, " + what);
    const RepairResult r = repair(preset);
    const std::string outcome = r.found ? (r.fraction >= 1.0 ? "repaired over the whole interval"
                                                             : "repaired over " + format_short(100.0 * r.fraction) + " % of it")
                                        : "NOT repaired";
    add("repair." + id + "_s",
        "phedra repair of " + what + " (" + std::to_string(r.before.panels) + " panels): " + outcome + ", " +
            std::to_string(r.evaluations) + " designs built, distance " + format_short(r.distance),
        r.seconds, "s", target);
  }

  void repair_figures() {
    repair_one("default_size", "the default preset before it was made buildable (10 bow-ties, a collision at t*)",
               unbuildable_default_preset(), 1.0);
    const std::size_t strips = options_.quick ? 20 : 100;
    repair_one("strips_" + std::to_string(strips),
               "a helical open design of " + std::to_string(strips) + " strips with a height moved too far (a column of bow-ties)",
               unbuildable_open_preset(strips), options_.quick ? std::optional<double>() : std::optional<double>(10.0));
  }

  void optimize_one(const std::string& id, const std::string& what, const nlohmann::json& preset,
                    const std::string& target, std::optional<double> goal) {
    announce("optimize, " + what);
    OptimizeOptions o;
    o.targets = {FigureTarget::parse(target)};
    const OptimizeResult r = optimize(preset, o);
    add("optimize." + id + "_s",
        "phedra optimize of " + what + " to " + target + ": " + (r.reached ? "reached" : "NOT reached") + ", " +
            std::to_string(r.evaluations) + " designs built, " + std::to_string(r.changes.size()) + " fields changed",
        r.reached ? r.seconds : std::numeric_limits<double>::infinity(), "s", goal);
  }

  void optimize_figures() {
    // The grid's Poisson's ratio along/across its tubes made auxetic (1.50 -> -0.8).
    optimize_one("grid_3x3", "the 3 x 3 grid preset",
                 preset_object(parse_json_text(read_text_file(std::string(PHEDRA_PRESETS_DIR) + "/grid-3x3.json"))), "poisson.nu_12=-0.8", 10.0);
    const std::size_t strips = options_.quick ? 20 : 100;
    const nlohmann::json helix = designer_helix_preset(strips);
    const double nu = *metamaterial_metrics(design_from_json(helix), {.samples = 2}).figure("poisson.nu_13");
    optimize_one("strips_" + std::to_string(strips), "a helical open design of " + std::to_string(strips) + " strips",
                 helix, "poisson.nu_13=" + format_short(nu + 0.3), options_.quick ? std::optional<double>() : std::optional<double>(60.0));
  }

  struct ModesSeconds {
    double best = 0.0;   ///< of three runs (the bench's default)
    double first = 0.0;  ///< the first of them (the design's first analysis in the process)
    std::size_t panels = 0;
  };
  /// The model, K and 6 eigenpairs (n5b8) of `design` at t*, three runs. Each
  /// allocates its factor afresh: on a VM whose host takes back freed memory, a
  /// run whose factor lands on memory the host no longer backs pays for its
  /// first touch (docs/performance.md, session 36), so the first run is kept too.
  ModesSeconds modes_seconds(const Design& design, std::string* model_name = nullptr) {
    ModesSeconds out;
    const StiffnessOptions options = default_stiffness(design);  // n5b8 unless a panel is not convex
    if (model_name) *model_name = to_string(options.panels);
    bool first = true;
    out.best = best_seconds(
        [&] {
          const auto start = Clock::now();
          AssemblyConfiguration c;
          std::vector<Points> rates;
          design.assembly.evaluate_rate(design.assembly.t_star(), c, rates);
          const BarHingeModel model(design, c, options);
          Points v;
          model.node_rates(rates, v);
          const ModeAnalysis a = analyze_modes(model, flatten(v), 6);
          out.panels = model.panels().size();
          keep(&a);
          if (first) out.first = std::chrono::duration<double>(Clock::now() - start).count();
          first = false;
        },
        0.0, 3, 3);
    return out;
  }

  void mechanics_figures() {
    // One core: BLAS is Debian's serial OpenBLAS, and CHOLMOD's OpenMP loops (a fixed 4
    // threads in Debian's CHOLMOD) run on the calling thread (mechanics/src/cholmod_threads.h).
    const std::size_t cells = options_.quick ? 3 : 10;
    {
      announce("mechanics, the stiffness's modes of arrays");
      // A 3D lattice (cells x cells tubes along the trajectory), and as a growth check one of a quarter the panels.
      const std::size_t segments = options_.quick ? 10 : 45;
      const ModesSeconds small = modes_seconds(mechanics_array(cells, segments / 4));
      std::string model;
      const ModesSeconds large = modes_seconds(mechanics_array(cells, segments), &model);
      add("mechanics.modes_array_s",
          "the bar-and-hinge model (" + model + "), K and its 6 smallest non-rigid eigenpairs (and the rigid-body count, the "
          "largest eigenvalue, the alignment) of a " + std::to_string(cells) + " x " + std::to_string(cells) + " array, " +
              std::to_string(large.panels) + " panels (a 3D lattice of tubes: tests/data/grid-10x10.json), the best of 3 runs",
          large.best, "s", options_.quick ? std::nullopt : std::optional<double>(2.0));
      add("mechanics.modes_array_first_s",
          "the first of those runs (as a one-shot `phedra mechanics`: its factor on memory touched for the first time)",
          large.first, "s");
      add("mechanics.modes_array_growth",
          "its time over that of " + std::to_string(small.panels) + " panels (" + format_short(small.best) + " s), per " +
              format_short(static_cast<double>(large.panels) / static_cast<double>(small.panels)) + " times the panels",
          large.best / small.best, "x");
    }
    {
      announce("mechanics, the energy landscape");
      const Design array = mechanics_array(cells, options_.quick ? 10 : 45);
      const Assembly& a = array.assembly;
      EnergyOptions e;
      e.rest_t = a.t_star();
      e.samples = 1000;
      e.stiffness = default_stiffness(array);
      std::size_t folds = 0;
      // The best of three, as the modes' figure: two threads on a shared machine vary more than one.
      const double seconds = best_seconds([&] { folds = energy_landscape(array, e).folds; }, 0.0, 3, 3);
      e.samples = 250;
      const double quarter = best_seconds([&] { folds = energy_landscape(array, e).folds; }, 0.0, 2, 2);
      add("mechanics.energy_1000_s",
          "the exact energy landscape of 1000 samples (E, dE/dt, equilibria, forces) of the same array, " +
              std::to_string(folds) + " fold springs, two threads, the best of 3 runs",
          seconds, "s", options_.quick ? std::nullopt : std::optional<double>(0.2));
      add("mechanics.energy_samples_growth", "its time over that of 250 samples (" + format_short(quarter) + " s)",
          seconds / quarter, "x");
    }
    {
      announce("mechanics, the gap over the interval");
      ControlPolylines input = parallelogram_array(1, 25).assembly.base().input();
      const Design tube = single_design(input);
      std::size_t panels = 0;
      const double seconds = best_seconds(
          [&] {
            const ModesOverInterval m = modes_over_interval(tube, 200, default_stiffness(tube), 6);
            panels = tube.assembly.topology(0).face_count();
            keep(&m);
          },
          0.0, 2, 2);
      add("mechanics.gap_200_tube_s",
          "the 6 smallest modes, tracked, and the gap at 200 configurations of a parallelogram tube of " +
              std::to_string(panels) + " panels (n5b8)",
          seconds, "s", options_.quick ? std::nullopt : std::optional<double>(1.0));
    }
  }

  const BenchOptions& options_;
  const std::function<void(const std::string&)>& progress_;
  BenchReport report_;
};

}  // namespace

const std::vector<std::string>& bench_groups() {
  static const std::vector<std::string> groups{"memory", "evaluate", "accuracy", "interval", "closure",
                                               "gltf",   "repair",   "optimize", "mechanics"};
  return groups;
}

bool BenchReport::all_met() const {
  return std::all_of(figures.begin(), figures.end(), [](const Figure& f) { return f.met(); });
}

nlohmann::json BenchReport::to_json() const {
  nlohmann::json j;
  j["quick"] = quick;
  j["machine"] = machine;
  j["all_targets_met"] = all_met();
  j["figures"] = nlohmann::json::array();
  for (const Figure& f : figures) {
    nlohmann::json e{{"id", f.id}, {"description", f.description}, {"value", f.value}, {"unit", f.unit}};
    if (f.target) {
      e["target"] = *f.target;
      e["met"] = f.met();
    }
    j["figures"].push_back(e);
  }
  return j;
}

std::ostream& operator<<(std::ostream& out, const BenchReport& report) {
  out << "phedra bench" << (report.quick ? " --quick (small cases: not comparable with the targets)" : "") << "\n"
      << "machine: " << report.machine << "\n\n";
  for (const Figure& f : report.figures) {
    std::ostringstream value;
    value << std::setprecision(4) << f.value << " " << f.unit;
    out << std::left << std::setw(42) << f.id << std::setw(22) << value.str() << " ";
    if (f.target) {
      std::ostringstream target;
      target << "<= " << std::setprecision(4) << *f.target;
      // A quick run's small cases say nothing about the targets: no verdict.
      out << std::setw(12) << target.str() << (report.quick ? "(quick)" : f.met() ? "met    " : "MISSED ");
    } else {
      out << std::setw(19) << "";
    }
    out << f.description << "\n";
  }
  out << "\n"
      << (report.quick ? "quick run: small cases, not compared with the targets (run without --quick for that)"
          : report.all_met() ? "every target met"
                             : "some targets missed")
      << "\n";
  return out;
}

BenchReport run_benchmarks(const BenchOptions& options, const std::function<void(const std::string&)>& progress) {
  return Runner(options, progress).run();
}

}  // namespace phedra::bench
