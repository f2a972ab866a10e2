// `sedwave theory`: the 1D chain dispersion at given dimensionless frequencies, as CSV.
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "option_checks.hpp"
#include "sedwave/forward/catalog/models.hpp"

namespace sedwave::app {
namespace {

/// No NaN or infinity is printed as a value: such a point is refused with its reason. The one
/// place the chains have one is the undamped lattice's band edge omega_hat = 2, where the group
/// velocity vanishes and the derivatives diverge.
void require_finite(const forward::DispersionPoint& p, double omega_hat, double gamma_hat, bool derivatives) {
  const std::array<double, 2> values{p.alpha_hat, p.c_hat};
  const std::array<double, 4> slopes{p.d_alpha_hat.d_omega_hat, p.d_alpha_hat.d_gamma_hat, p.d_c_hat.d_omega_hat,
                                     p.d_c_hat.d_gamma_hat};
  bool finite = std::isfinite(values[0]) && std::isfinite(values[1]);
  if (derivatives) {
    for (double s : slopes) finite = finite && std::isfinite(s);
  }
  if (finite) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "omega_hat = %.17g, gamma_hat = %.17g: the model has no finite %s there (%s)", omega_hat, gamma_hat,
                std::isfinite(values[0]) && std::isfinite(values[1]) ? "derivatives" : "value",
                gamma_hat == 0.0 && std::abs(omega_hat - 2.0) < 1e-6
                    ? "the undamped lattice's band edge, where the group velocity vanishes"
                    : "overflow: use a smaller omega_hat");
  throw std::domain_error(text);
}

}  // namespace

Command add_theory_command(CLI::App& app) {
  struct Options {
    std::string model = "continuum";
    double gamma_hat = 0.0;
    std::vector<double> omega_hat;
    bool derivatives = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("theory", "Print alpha_hat and c_hat of a 1D chain model as CSV "
                                               "(dimensionless; see docs/physics.md)");
  cmd->add_option("--model", o->model, "continuum | lattice")->check(CLI::IsMember({"continuum", "lattice"}));
  cmd->add_option("--gamma-hat", o->gamma_hat, "dimensionless dashpot gamma/sqrt(kappa m), 0 .. 1e6")
      ->required()
      ->check(finite_in(0.0, 1e6));
  cmd->add_option("--omega-hat", o->omega_hat,
                  "comma-separated dimensionless frequencies omega sqrt(m/kappa), > 0 and <= 1e6")
      ->required()
      ->delimiter(',')
      ->check(finite_in(1e-300, 1e6));
  cmd->add_flag("--derivatives", o->derivatives, "also print d/d omega_hat and d/d gamma_hat of alpha_hat and c_hat");
  return {cmd, [o]() {
    const auto model = forward::make_dispersion_model(o->model);
    std::vector<forward::DispersionPoint> points;
    for (double w : o->omega_hat) {
      points.push_back(model->evaluate(w, o->gamma_hat));
      require_finite(points.back(), w, o->gamma_hat, o->derivatives);
    }
    std::printf("omega_hat,gamma_hat,k_hat,alpha_hat,c_hat%s\n",
                o->derivatives ? ",dalpha_domega,dalpha_dgamma,dc_domega,dc_dgamma" : "");
    for (size_t i = 0; i < points.size(); ++i) {
      const double w = o->omega_hat[i];
      const forward::DispersionPoint& p = points[i];
      std::printf("%.17g,%.17g,%.17g,%.17g,%.17g", w, o->gamma_hat, w / p.c_hat, p.alpha_hat, p.c_hat);
      if (o->derivatives) {
        std::printf(",%.17g,%.17g,%.17g,%.17g", p.d_alpha_hat.d_omega_hat, p.d_alpha_hat.d_gamma_hat,
                    p.d_c_hat.d_omega_hat, p.d_c_hat.d_gamma_hat);
      }
      std::printf("\n");
    }
    return 0;
  }};
}

}  // namespace sedwave::app
