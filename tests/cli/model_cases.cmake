# Sediment models on the command line (`sedwave models`, `invert --model`, `synthesize --model`):
# every model is listed with its parameters; unknown models and parameters are refused with the
# accepted ones; values outside a parameter's physical range are refused with the range.
set(OBS ${PROJECT_SOURCE_DIR}/data/field/zhou2009_regression.csv)
set(FAST --no-plot --method ceres --out ${CLI_OUT}/models_never)

# (expect.sh matches one line: one case per line that must be there)
sedwave_cli_case(models.lists_the_saturated_frame 0 "^saturated-lattice: granular frame 'lattice' saturated" models)
sedwave_cli_case(models.lists_vgs_parameters 0 "^  tau_p +s +0.00012 +\\[1e-09, 1e\\+03\\]" models)
sedwave_cli_case(models.lists_derived_quantities 0 "^  biot_frequency +Hz +\\[0.1, 2e\\+11\\] +Biot.s characteristic frequency" models biot-stoll)
sedwave_cli_case(models.one_model 0 "^  permeability +m\\^2 +4e-11 +\\[1e-20, 1e-05\\]" models edfm)
# An empty name given (an unset shell variable) is refused as `compare --models ''` is, not read as "all".
add_test(NAME cli.models.empty_name COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "models '': an empty model name"
  -- sh -c "exec \"$0\" models ''" $<TARGET_FILE:sedwave>)
sedwave_cli_case(models.unknown 1 "unknown model 'bort'.*accepted: continuum, lattice.*vgs-lambda" models bort)
sedwave_cli_case(invert.model_typical_fit 0 "^  porosity +\\[1 +\\] 0\\.44[0-9]* \\+- " invert ${OBS} --model biot-stoll ${FAST})
sedwave_cli_case(invert.model_unknown_parameter 1 "--fit 'kappa': unknown parameter 'kappa'.*accepted: porosity"
  invert ${OBS} --model edfm --fit kappa ${FAST})
sedwave_cli_case(invert.set_unknown_parameter 2 "--set: unknown parameter 'porosty'.*accepted: porosity"
  invert ${OBS} --model edfm --fit permeability --set porosty=0.4 ${FAST})
sedwave_cli_case(invert.set_outside_physical_range 1 "porosity \\(value 1.5.*physical range \\[0.01, 0.99\\]"
  invert ${OBS} --model edfm --fit permeability --set porosity=1.5 ${FAST})
sedwave_cli_case(invert.bounds_outside_physical_range 1 "n \\(value .*search bounds \\[0.001, 2\\]\\).*physical range \\[0.001, 0.99\\]"
  invert ${OBS} --model grain-shearing --fit n --bounds n=0.001,2 ${FAST})
sedwave_cli_case(invert.set_not_a_number 2 "--set 'porosity=abc': 'abc' is not a finite number"
  invert ${OBS} --model edfm --fit permeability --set porosity=abc ${FAST})
sedwave_cli_case(invert.kappa_for_model_without_contacts 2 "--kappa: unknown parameter 'kappa'.*model 'edfm'"
  invert ${OBS} --model edfm --fit permeability --kappa 1e6 ${FAST})
# The water-saturated frame on the shipped field data: a fit, with a sand looser than any sand flagged.
sedwave_cli_case(invert.saturated_frame_flags_mud_porosity 3 "! porosity = 0.8[0-9]* with sand-sized grains"
  invert ${OBS} --model saturated-lattice --fit kappa,gamma,porosity,permeability --d 3e-4 ${FAST})

# Synthesize with a model, then fit it back: the truth is recovered (EDFM: porosity and permeability).
sedwave_cli_case(synthesize.edfm 0 "24 observations from edfm"
  synthesize --model edfm --set porosity=0.42 --set permeability=3e-11 --from 100 --to 1e5 --points 12
  --alpha-noise 0.02 --speed-noise 0.003 --out ${CLI_OUT}/edfm_synthetic.csv)
set_tests_properties(cli.synthesize.edfm PROPERTIES FIXTURES_SETUP edfm_synthetic)
sedwave_cli_case(invert.edfm_recovers_its_porosity 0 "^  porosity +\\[1 +\\] 0\\.4[12][0-9]* \\+- 0\\.00[0-9]+ "
  invert ${CLI_OUT}/edfm_synthetic.csv --model edfm --fit porosity,permeability ${FAST})
set_tests_properties(cli.invert.edfm_recovers_its_porosity PROPERTIES FIXTURES_REQUIRED edfm_synthetic)
sedwave_cli_case(invert.edfm_recovers_its_permeability 0 "^  permeability +\\[m\\^2 \\] (2\\.9|3\\.0|3\\.1)[0-9]*e-11 \\+- "
  invert ${CLI_OUT}/edfm_synthetic.csv --model edfm --fit porosity,permeability ${FAST})
set_tests_properties(cli.invert.edfm_recovers_its_permeability PROPERTIES FIXTURES_REQUIRED edfm_synthetic)

# Site inputs (docs/models/site-inputs.md): what they set is printed; a parameter set twice, or one
# the model lacks, is refused.
sedwave_cli_case(invert.site_phi_sets_d 0 "^site: d = 0.0002973 m from phi 1.75 \\(medium sand\\)"
  invert ${OBS} --model saturated-lattice --fit gamma,permeability --phi 1.75 --bulk-density 1950 --depth 1
  --water-temperature 15 --salinity 35 ${FAST})
sedwave_cli_case(invert.site_depth_sets_kappa_from_hertz 0 "^site: kappa = 6.909e\\+04 N/m: Hertz, quartz grains .* at 6041 Pa"
  invert ${OBS} --model saturated-lattice --fit gamma,permeability --phi 1.75 --bulk-density 1950 --depth 1
  --water-temperature 15 --salinity 35 ${FAST})
sedwave_cli_case(invert.site_phi_and_d 2 "--phi and --d both set d: give one"
  invert ${OBS} --phi 2 --d 3e-4 ${FAST})
sedwave_cli_case(invert.site_depth_without_contacts 2 "--depth: model 'edfm' has no parameter 'kappa'"
  invert ${OBS} --model edfm --fit permeability --depth 1 ${FAST})
sedwave_cli_case(invert.site_temperature_needs_salinity 2 "--water-temperature and --salinity go together"
  invert ${OBS} --model edfm --fit permeability --water-temperature 10 ${FAST})
sedwave_cli_case(invert.site_temperature_outside_mackenzie 1 "temperature T = 35 deg C lies outside the accepted range \\[2, 30\\]"
  invert ${OBS} --model edfm --fit permeability --water-temperature 35 --salinity 35 ${FAST})

# The Bayesian posterior (--method posterior): priors printed with their source, credible intervals,
# R-hat and ESS; an interval the prior made is flagged (d, unseen, and kappa, which c0 ties to it);
# bad priors are refused. d's posterior is its prior: median 3e-4 m, 68 % interval
# 3e-4 e^-+0.3 = 2.22e-4 .. 4.05e-4 m, to Monte Carlo error.
sedwave_cli_case(invert.posterior_prior_on_d 3 "^  d +m +0.000(29|30)[0-9]* +0.0002[12][0-9]* \\.\\. 0.000(39|40|41)[0-9]* .*PRIOR-CONTROLLED \\(prior's share (99|100) %\\)"
  invert ${OBS} --method posterior --prior d=log-normal:3e-4,0.3 --steps 4000 --no-plot --out ${CLI_OUT}/posterior)
sedwave_cli_case(invert.posterior_flags_a_ridge_parameter 3 "^  kappa +N/m .*PRIOR-CONTROLLED \\(prior's share"
  invert ${OBS} --method posterior --prior d=log-normal:3e-4,0.3 --steps 4000 --no-plot --out ${CLI_OUT}/posterior_ridge)
sedwave_cli_case(invert.posterior_lists_priors 3 "^    d: log-normal\\(median 0.0003 m, sd of ln 0.3\\) on the bounds .*\\(command line\\)"
  invert ${OBS} --method posterior --prior d=log-normal:3e-4,0.3 --steps 4000 --no-plot --out ${CLI_OUT}/posterior2)
sedwave_cli_case(invert.prior_without_posterior 2 "--prior is for --method posterior"
  invert ${OBS} --prior d=log-normal:3e-4,0.3 ${FAST})
sedwave_cli_case(invert.prior_unknown_kind 1 "unknown kind 'gauss' \\(accepted: uniform:A,B"
  invert ${OBS} --method posterior --prior d=gauss:1,2 --no-plot --out ${CLI_OUT}/posterior_never)
sedwave_cli_case(invert.prior_on_fixed_parameter 1 "rho_s is fixed. name it in --fit to give it a prior"
  invert ${OBS} --method posterior --prior rho_s=normal:2650,50 --no-plot --out ${CLI_OUT}/posterior_never)
# The run length adapts; only a run that reaches the cap (--steps) ends NOT CONVERGED, saying so.
sedwave_cli_case(invert.posterior_not_converged 3 "NOT CONVERGED: stopped at the cap of 40 steps \\(--steps\\) before converging: .*run more steps"
  invert ${OBS} --method posterior --steps 40 --no-plot --out ${CLI_OUT}/posterior_short)

# Model comparison by evidence (sedwave compare). COMPARE_FAST caps the run below the 500 steps
# the evidence's error needs before it is trusted, so those runs end NOT CONVERGED (exit 3).
set(COMPARE_FAST --steps 400 --temperatures 16)
sedwave_cli_case(compare.unknown_model 1 "unknown model 'bort'.*accepted: continuum"
  compare ${OBS} --models edfm,bort ${COMPARE_FAST} --out ${CLI_OUT}/compare_never)
sedwave_cli_case(compare.prior_no_model_has 2 "--prior 'kappa=log-normal:1e6,1': none of the models has a parameter 'kappa'"
  compare ${OBS} --models edfm,grain-shearing --prior kappa=log-normal:1e6,1 ${COMPARE_FAST} --out ${CLI_OUT}/compare_never)
sedwave_cli_case(compare.fit_names_parameter_of_another_model 1 "--fit 'lattice=porosity' \\(the parameters of lattice\\): unknown parameter 'porosity'.*accepted: kappa, d, gamma, rho_s"
  compare ${OBS} --models lattice,edfm --fit lattice=porosity ${COMPARE_FAST} --out ${CLI_OUT}/compare_never)
sedwave_cli_case(compare.fit_for_model_not_compared 2 "--fit 'lattice=kappa,d': 'lattice' is not one of --models"
  compare ${OBS} --models edfm,grain-shearing --fit lattice=kappa,d ${COMPARE_FAST} --out ${CLI_OUT}/compare_never)

# Site files (docs/inversion.md, "Site files"): priors with their source; mistakes named by file,
# line and key; a site value that clashes with a direct one is refused.
set(SITE ${PROJECT_SOURCE_DIR}/data/sites/medium_sand.toml)
sedwave_cli_case(invert.site_file_priors 3 "^    d: log-normal\\(median 0.0002973 m, sd of ln 0.3466\\) .*\\(site file .*medium_sand.toml\\)"
  invert ${OBS} --method posterior --site ${SITE} --steps 1000 --no-plot --out ${CLI_OUT}/site_posterior)
sedwave_cli_case(invert.site_file_misspelt_key 1 "misspelt.toml:3: key 'grain_size.phi_sdd': unknown key"
  invert ${OBS} --site ${CLI_DATA}/site/misspelt.toml ${FAST})
sedwave_cli_case(invert.site_file_out_of_range 1 "porosity_out_of_range.toml:2: key 'porosity.mean' = 1.4: accepted range \\(0, 1\\)"
  invert ${OBS} --site ${CLI_DATA}/site/porosity_out_of_range.toml ${FAST})
sedwave_cli_case(invert.site_file_depth_needs_grain_size 1 "depth_without_grain_size.toml:2: key 'depth.metres': the Hertz stiffness needs the grain size"
  invert ${OBS} --site ${CLI_DATA}/site/depth_without_grain_size.toml ${FAST})
sedwave_cli_case(invert.site_file_and_direct_value 2 "medium_sand.toml:7: key 'grain_size.phi' and --d both set d: give one"
  invert ${OBS} --site ${SITE} --d 3e-4 ${FAST})
sedwave_cli_case(invert.site_file_and_site_option 2 "medium_sand.toml:7: key 'grain_size.phi' and --phi both set d"
  invert ${OBS} --site ${SITE} --phi 2 ${FAST})
# The same site as a file and as options: identical fixed values, kappa included.
add_test(NAME cli.site.file_matches_flags
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/site_file_matches_flags.sh $<TARGET_FILE:sedwave> ${OBS} ${SITE} ${CLI_OUT}/site_file_matches_flags)

# The posterior's band over the data and its samples as HDF5 (compare's bands of every model: the
# threads case below).
sedwave_cli_case(invert.posterior_writes_band_and_hdf5 3 "samples: .*posterior_samples.csv and .h5, band over the data: .*posterior_predictive.csv"
  invert ${OBS} --method posterior --steps 200 --threads 2 --no-plot --out ${CLI_OUT}/posterior_band)
sedwave_cli_case(compare.threads_must_be_a_count 2 "--threads: Value -1 not in range"
  compare ${OBS} --models edfm --threads -1 --out ${CLI_OUT}/compare_never)
# The models' jobs run side by side on the default thread count; the results are those of 1 thread.
# The same two runs check the ranking line, the posterior bands and the plots.
add_test(NAME cli.compare.threads_give_the_same_results
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/compare_threads_agree.sh $<TARGET_FILE:sedwave> ${OBS} ${CLI_OUT}/compare_threads)
# A model far below another (the lattice on EDFM's data) gets its ln Z as a labelled upper bound.
add_test(NAME cli.compare.states_a_bound_far_below
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/compare_states_a_bound.sh $<TARGET_FILE:sedwave> ${CLI_OUT}/compare_bound)
# A combination made of fixed parameters only (c0 with d from --phi and kappa from --depth) is known
# exactly, and checked for plausibility like a fitted value.
sedwave_cli_case(invert.fixed_combination_is_checked 3 "! c0 = 409.3 is below the physical range"
  invert --digitized-file ${PROJECT_SOURCE_DIR}/data/digitized/example_webplotdigitizer.csv
  --digitized attenuation:kHz:dB/m:0.1 --water-speed 1500 --phi 2.3 --depth 1 --fit gamma --no-plot
  --out ${CLI_OUT}/fixed_combination)
