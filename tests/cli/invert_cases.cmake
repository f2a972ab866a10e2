# `sedwave invert`, `theory` and `synthesize`: conflicting or meaningless options, unusable sigmas,
# outputs that would overwrite inputs, and results outside physical ranges. Exit codes: 1 error,
# 2 usage (the command line itself), 3 ran but flagged (docs/cli.md).
set(OBS ${PROJECT_SOURCE_DIR}/data/field/zhou2009_regression.csv)
set(INV ${CLI_DATA}/invert)
set(FAST --no-plot --method ceres --out ${CLI_OUT}/invert_never)

sedwave_cli_case(invert.fit_names_gamma_and_en 1 "damping is one parameter.*name both" invert ${OBS} --fit kappa,d,gamma,en ${FAST})
sedwave_cli_case(invert.fit_gamma_en_only 1 "damping is one parameter.*name both" invert ${OBS} --fit gamma,en ${FAST})
sedwave_cli_case(invert.fit_names_kappa_twice 1 "names 'kappa' twice" invert ${OBS} --fit kappa,kappa ${FAST})
sedwave_cli_case(invert.fit_unknown_parameter 1 "unknown parameter 'rho'.*accepted: kappa, d, gamma, rho_s"
  invert ${OBS} --fit kappa,rho ${FAST})
sedwave_cli_case(invert.gamma_and_en_values 1 "damping is one parameter" invert ${OBS} --gamma 1 --en 0.5 ${FAST})
sedwave_cli_case(invert.fit_en_with_gamma_bounds 1 "damping is one parameter"
  invert ${OBS} --fit kappa,en --gamma-bounds 1,10 ${FAST})
sedwave_cli_case(invert.fit_gamma_with_en_value 1 "damping is one parameter" invert ${OBS} --fit kappa,gamma --en 0.3 ${FAST})
sedwave_cli_case(invert.negative_determined_log_sigma 2 "--determined-log-sigma.*outside the accepted range"
  invert ${OBS} --determined-log-sigma -1 ${FAST})
sedwave_cli_case(invert.negative_default_sigma 2 "--default-sigma.*outside the accepted range"
  invert ${OBS} --default-sigma -1 ${FAST})
sedwave_cli_case(invert.zero_default_sigma 2 "--default-sigma.*outside the accepted range"
  invert ${INV}/no_sigma.csv --default-sigma 0 ${FAST})
sedwave_cli_case(invert.nan_default_sigma 2 "--default-sigma.*not a finite number"
  invert ${INV}/no_sigma.csv --default-sigma nan ${FAST})
sedwave_cli_case(invert.zero_max_evaluations 2 "--max-evaluations.*not in range" invert ${OBS} --max-evaluations 0 ${FAST})
sedwave_cli_case(invert.negative_max_evaluations 2 "--max-evaluations.*not in range"
  invert ${OBS} --max-evaluations -5 ${FAST})
sedwave_cli_case(invert.nan_kappa 2 "--kappa.*not a finite number" invert ${OBS} --kappa nan ${FAST})
sedwave_cli_case(invert.negative_d 2 "--d.*outside the accepted range" invert ${OBS} --d -3e-4 ${FAST})
sedwave_cli_case(invert.en_above_one 2 "--en.*outside the accepted range" invert ${OBS} --fit kappa,en --en 1.5 ${FAST})
sedwave_cli_case(invert.reversed_bounds 1 "bounds of kappa .* must satisfy 0 < lower < upper"
  invert ${OBS} --kappa-bounds 10,1 ${FAST})
sedwave_cli_case(invert.start_outside_bounds 1 "kappa = 1e\\+09 N/m lies outside its bounds"
  invert ${OBS} --kappa 1e9 --kappa-bounds 1,10 ${FAST})
sedwave_cli_case(invert.sigma_1e-300 1 "tiny_sigma.csv:3: field 'sigma' = 1e-300 is not usable"
  invert ${INV}/tiny_sigma.csv ${FAST})
sedwave_cli_case(invert.sigma_1e-300_global 1 "tiny_sigma.csv:3: field 'sigma' = 1e-300 is not usable"
  invert ${INV}/tiny_sigma.csv --no-plot --method global --out ${CLI_OUT}/invert_never)
sedwave_cli_case(invert.water_speed_nan 2 "--water-speed.*not a finite number" invert ${OBS} --water-speed nan ${FAST})
sedwave_cli_case(invert.out_overwrites_input 2 "names the input|would overwrite|overwrite"
  IN ${INV}/overwrite invert observations.csv --no-plot --method ceres --out .)
sedwave_cli_case(invert.out_not_writable 1 "--out /proc/sedwave-cannot-write"
  invert ${OBS} --no-plot --out /proc/sedwave-cannot-write)
sedwave_cli_case(invert.no_observation_files 1 "no observation files given" invert ${FAST})
sedwave_cli_case(invert.unknown_model 1 "unknown model 'foo'.*accepted: continuum, lattice, .*biot-stoll" invert ${OBS} --model foo ${FAST})
sedwave_cli_case(invert.table_far_below_field_data 1 "make a long-wavelength table"
  invert ${OBS} --model table:${PROJECT_SOURCE_DIR}/data/tables/thesis_w3_small.h5 ${FAST})
# Results outside physical ranges are flagged (exit 3), never printed as plain answers.
sedwave_cli_case(invert.khz_read_as_hz_flags_slow_sediment 3 "c0 = [0-9.e+]+ is below the physical range.*kHz but read as Hz"
  invert --digitized-file ${PROJECT_SOURCE_DIR}/data/digitized/example_webplotdigitizer.csv
  --digitized attenuation:Hz:dB/m:0.1 --water-speed 1500 --fit kappa,gamma --d 2e-4 --no-plot --out ${CLI_OUT}/invert_khz)
sedwave_cli_case(invert.parameter_at_bound_is_flagged 3 "kappa stopped at its search bound"
  invert ${OBS} --fit kappa,gamma --d 3e-4 --kappa-bounds 1e3,1e4 --kappa 5e3 --no-plot --out ${CLI_OUT}/invert_bound)

sedwave_cli_case(theory.lattice_band_edge_derivatives 1 "band edge"
  theory --model lattice --gamma-hat 0 --omega-hat 2 --derivatives)
sedwave_cli_case(theory.omega_hat_1e300 2 "--omega-hat.*outside the accepted range" theory --gamma-hat 0 --omega-hat 1e300)
sedwave_cli_case(theory.negative_gamma_hat 2 "--gamma-hat.*outside the accepted range" theory --gamma-hat -1 --omega-hat 1)
sedwave_cli_case(theory.nan_omega_hat 2 "--omega-hat.*not a finite number" theory --gamma-hat 1 --omega-hat nan)
sedwave_cli_case(synthesize.nan_kappa 2 "--kappa.*not a finite number"
  synthesize --kappa nan --d 3e-4 --gamma 1 --from 1e3 --to 1e5 --out ${CLI_OUT}/never.csv)
sedwave_cli_case(synthesize.band_upside_down 1 "--from must be below --to"
  synthesize --kappa 1e6 --d 3e-4 --gamma 1 --from 1e5 --to 1e3 --out ${CLI_OUT}/never.csv)
sedwave_cli_case(synthesize.gamma_and_en 2 "excludes" 
  synthesize --kappa 1e6 --d 3e-4 --gamma 1 --en 0.5 --from 1e3 --to 1e5 --out ${CLI_OUT}/never.csv)

# Writing to a full device: an error and a non-zero exit, never exit 0 with the output lost.
add_test(NAME cli.theory.stdout_full_disk
  COMMAND sh -c "$<TARGET_FILE:sedwave> theory --gamma-hat 0 --omega-hat 0.5 > /dev/full")
set_tests_properties(cli.theory.stdout_full_disk PROPERTIES WILL_FAIL TRUE)
# kill -9 at any moment of `invert` leaves the previous outputs whole (each is renamed into place).
add_test(NAME cli.invert.kill_9_keeps_previous_outputs
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/kill_during_invert.sh $<TARGET_FILE:sedwave> ${OBS} ${CLI_OUT}/kill9)
# Bottom loss against grazing angle (docs/reflection.md, "Fitting bottom-loss data"): noise-free EDFM
# data (porosity 0.42, permeability 3e-11 m^2) fitted back; eta and permeability enter the bottom
# loss nearly as one ratio, so fitting both leaves them NOT DETERMINED; a row without its angle.
sedwave_cli_case(invert.bottom_loss_halfspace 0 "^  porosity +\\[1   \\] 0\\.42 \\+- 0\\.004"
  invert ${INV}/bottom_loss_edfm.csv --model edfm --fit porosity,permeability ${FAST})
sedwave_cli_case(invert.bottom_loss_unseen_parameter 0 "^  eta +\\[Pa s\\] NOT DETERMINED by these data"
  invert ${INV}/bottom_loss_edfm.csv --model edfm --fit porosity,permeability,eta ${FAST})
sedwave_cli_case(invert.bottom_loss_without_angle 1 "bottom_loss_no_angle\\.csv:4:7: field 'grazing_angle_deg': a reflection row needs its grazing angle"
  invert ${INV}/bottom_loss_no_angle.csv --model edfm ${FAST})

# One measurement repeated: the posterior flags every quantity the data cannot place, however its
# ridge curves through the priors' box.
add_test(NAME cli.invert.prior_flag_one_frequency
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/prior_flag_one_frequency.sh $<TARGET_FILE:sedwave>
          ${CMAKE_CURRENT_SOURCE_DIR}/data/invert/one_attenuation_ten_times.csv)
# The water an observation file declares has a physical range, named with its file, line and field.
sedwave_cli_case(invert.file_water_density_huge 1 "water_density_huge\\.csv:2:28: field 'water_density_kg_per_m3': water density 1e308 kg/m\\^3 is outside \\[950, 1300\\]"
  invert ${INV}/water_density_huge.csv --model edfm --fit porosity ${FAST})
sedwave_cli_case(invert.file_water_speed_huge 1 "water_speed_huge\\.csv:1:30: field 'water_sound_speed_m_per_s': sound speed 1e308 m/s is outside \\[100, 10000\\]"
  invert ${INV}/water_speed_huge.csv --model edfm --fit porosity ${FAST})

# Two solutions: Biot-Stoll's permeability either side of Biot's attenuation peak fits these four
# points over 200-210 Hz (made by `sedwave synthesize --model biot-stoll --set permeability=1e-9
# --from 200 --to 210 --points 4 --alpha-noise 0.05 --speed-noise 0.01 --seed 301`): the fit names
# the other local minimum and says the data hardly choose between them.
sedwave_cli_case(invert.second_solution_is_told 0
  "another local minimum of chi2 .*permeability [0-9.e+-]+ m\\^2.*hardly choose between the two solutions"
  invert ${CLI_DATA}/bimodal_biot_stoll.csv --model biot-stoll --fit porosity,permeability
  --out ${CLI_OUT}/second_solution --no-plot)
