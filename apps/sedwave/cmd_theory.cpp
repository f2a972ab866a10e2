// `sedwave theory`: the 1D chain dispersion at given dimensionless frequencies, as CSV.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "sedwave/forward/models.hpp"

namespace sedwave::app {

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
  cmd->add_option("--gamma-hat", o->gamma_hat, "dimensionless dashpot gamma/sqrt(kappa m) >= 0")->required();
  cmd->add_option("--omega-hat", o->omega_hat, "comma-separated dimensionless frequencies omega sqrt(m/kappa) > 0")
      ->required()
      ->delimiter(',');
  cmd->add_flag("--derivatives", o->derivatives, "also print d/d omega_hat and d/d gamma_hat of alpha_hat and c_hat");
  return {cmd, [o]() {
    const auto model = forward::make_dispersion_model(o->model);
    std::printf("omega_hat,gamma_hat,k_hat,alpha_hat,c_hat%s\n",
                o->derivatives ? ",dalpha_domega,dalpha_dgamma,dc_domega,dc_dgamma" : "");
    for (double w : o->omega_hat) {
      const forward::DispersionPoint p = model->evaluate(w, o->gamma_hat);
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
