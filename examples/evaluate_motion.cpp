// Using phedra as a library: load a preset, read its flexion interval, evaluate
// the folding motion and check it. Built as `phedra_example_evaluate_motion`;
// run it with a preset path.

#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/phedron.h"
#include "phedra/preset.h"
#include "phedra/check_report.h"

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " PRESET\n";
    return 2;
  }
  try {
    const phedra::PHedron p(phedra::load_preset(argv[1]));
    const phedra::FlexionInterval& f = p.flexion_interval();
    std::cout << "t* = " << p.t_star() << ", flexion interval [" << f.lower.t << ", " << f.upper.t << "]\n";

    // Vertex positions at five parameters; reuse one buffer in a loop.
    phedra::Points vertices(p.vertex_count());
    for (int k = 0; k <= 4; ++k) {
      const double t = p.t_at_fraction(k / 4.0);
      p.evaluate(t, vertices);
      const phedra::Vec3& v = vertices[p.topology().index(p.topology().rows() - 1, 1)];  // V_{m,0}
      std::cout << "t = " << t << ": last trajectory point " << v.transpose() << "\n";
    }
    const phedra::IntervalCheckReport report = phedra::check_over_interval(p);
    std::cout << report;
    return report.passed() ? 0 : 1;
  } catch (const phedra::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return static_cast<int>(e.exit_code());
  }
}
