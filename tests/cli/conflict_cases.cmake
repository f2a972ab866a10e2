# Every output lands safely and every conflict is named (docs/cli.md): an option that would be
# ignored, or one value given through two options, is an error naming both; crashes on empty lists
# are errors; outputs to devices, FIFOs and links are written in place or refused, never replaced.
set(OBS ${PROJECT_SOURCE_DIR}/data/field/zhou2009_regression.csv)
set(FAST --no-plot --method ceres --out ${CLI_OUT}/conflict_never)
set(COMPARE_FAST --steps 400 --temperatures 16 --out ${CLI_OUT}/conflict_never)

# ---- One value, two options ---------------------------------------------------------------------
# (an empty argument cannot pass through a CMake list: these two go through sh)
add_test(NAME cli.conflict.fit_empty COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "--fit: an empty list names no parameter"
  -- sh -c "exec \"$0\" invert \"$1\" --fit '' --no-plot --method ceres --out \"$2\"" $<TARGET_FILE:sedwave> ${OBS}
  ${CLI_OUT}/conflict_never)
sedwave_cli_case(conflict.set_twice 2 "--set 'kappa=1e6' and --set 'kappa=2e6' both set kappa"
  invert ${OBS} --set kappa=1e6 --set kappa=2e6 ${FAST})
sedwave_cli_case(conflict.kappa_and_set_kappa 2 "--kappa and --set 'kappa=2e6' both set kappa"
  invert ${OBS} --kappa 1e6 --set kappa=2e6 ${FAST})
sedwave_cli_case(conflict.density_and_set_rho_s 2 "--density and --set 'rho_s=2700' both set rho_s"
  invert ${OBS} --density 2650 --set rho_s=2700 ${FAST})
sedwave_cli_case(conflict.bounds_twice 2 "--bounds 'kappa=1e5,1e7' and --bounds 'kappa=1e4,1e8' both bound kappa"
  invert ${OBS} --bounds kappa=1e5,1e7 --bounds kappa=1e4,1e8 ${FAST})
sedwave_cli_case(conflict.kappa_bounds_and_bounds 2 "--kappa-bounds and --bounds 'kappa=1e4,1e8' both bound kappa"
  invert ${OBS} --kappa-bounds 1e5,1e7 --bounds kappa=1e4,1e8 ${FAST})
sedwave_cli_case(conflict.bounds_on_fixed 2 "--bounds 'rho_s=2000,3000' bounds rho_s, which is fixed .*name it in --fit"
  invert ${OBS} --bounds rho_s=2000,3000 ${FAST})
sedwave_cli_case(conflict.d_bounds_on_fixed 2 "--d-bounds bounds d, which is fixed \\(--fit 'kappa,gamma'\\)"
  invert ${OBS} --fit kappa,gamma --d 3e-4 --d-bounds 1e-4,1e-3 ${FAST})
sedwave_cli_case(conflict.steps_without_posterior 2 "--steps is for --method posterior. --method ceres does not sample"
  invert ${OBS} --steps 500 ${FAST})
sedwave_cli_case(conflict.walkers_without_posterior 2 "--walkers is for --method posterior. --method global does not sample"
  invert ${OBS} --walkers 32 --no-plot --out ${CLI_OUT}/conflict_never)
sedwave_cli_case(conflict.temperatures_without_posterior 2 "--temperatures is for --method posterior. --method ceres does not sample"
  invert ${OBS} --method ceres --temperatures 8 --no-plot --out ${CLI_OUT}/conflict_never)

# ---- compare: its model list and per-model fits ------------------------------------------------------
add_test(NAME cli.conflict.compare_models_empty COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "--models '': name at least one model"
  -- sh -c "exec \"$0\" compare \"$1\" --models '' --out \"$2\"" $<TARGET_FILE:sedwave> ${OBS} ${CLI_OUT}/conflict_never)
sedwave_cli_case(conflict.compare_models_empty_item 2 "--models 'edfm,': an empty model name"
  compare ${OBS} --models edfm, ${COMPARE_FAST})
sedwave_cli_case(conflict.compare_models_twice 2 "--models 'lattice,lattice' names 'lattice' twice"
  compare ${OBS} --models lattice,lattice ${COMPARE_FAST})
sedwave_cli_case(conflict.compare_fit_empty 2 "--fit 'edfm=': an empty list names no parameter"
  compare ${OBS} --models edfm,grain-shearing --fit edfm= ${COMPARE_FAST})
sedwave_cli_case(conflict.compare_fit_twice 2 "--fit 'edfm=porosity' and --fit 'edfm=permeability' both choose the free parameters of edfm"
  compare ${OBS} --models edfm,grain-shearing --fit edfm=porosity --fit edfm=permeability ${COMPARE_FAST})

# ---- A pore fluid no sediment holds ------------------------------------------------------------
sedwave_cli_case(conflict.fluid_viscosity_1e3 1 [=[fluid_viscosity_1e3\.toml:71: key 'fluid\.viscosity' = 1000: accepted range \(0, 0\.1\] mu_hat]=]
  forward ${CLI_DATA}/scene/fluid_viscosity_1e3.toml --out ${CLI_OUT}/conflict_never.h5)

# ---- Outputs: devices, FIFOs, links; stale temporaries; one writer per --out --------------------------
add_test(NAME cli.outputs.devices_fifos_links
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/outputs_land_safely.sh $<TARGET_FILE:sedwave> ${CLI_DATA}/scene)
add_test(NAME cli.outputs.failed_run_and_lock
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/outputs_failed_run.sh $<TARGET_FILE:sedwave> ${OBS})
add_test(NAME cli.outputs.forward_one_writer
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/forward_one_writer.sh $<TARGET_FILE:sedwave> ${CLI_DATA}/scene/tiny.toml)

# ---- Results that cannot be right are flagged -----------------------------------------------------
sedwave_cli_case(conflict.synthesize_flags_impossible_speed 3 "! [0-9]+ of [0-9]+ sound speeds lie outside \\[100, 20000\\] m/s .*faster than any mineral"
  synthesize --kappa 1e12 --d 3e-4 --gamma 1 --from 1e3 --to 1e5 --points 4 --out ${CLI_OUT}/conflict_fast.csv)
sedwave_cli_case(conflict.models_lists_saturated_once 0 "^  pore_size +m "
  models saturated-lattice)
add_test(NAME cli.conflict.models_lists_saturated_frame_once
  COMMAND sh -c "test \"$($<TARGET_FILE:sedwave> models | grep -c '^saturated-lattice:')\" = 1")
add_test(NAME cli.conflict.show_flags_impossible_ok_points
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/show_flags_impossible_points.sh $<TARGET_FILE:sedwave>
          ${PROJECT_SOURCE_DIR}/data/tables/thesis_w3_small.h5)
# The corner plot is drawn (from the files the run has put in place) where gnuplot is installed.
find_program(GNUPLOT_PROGRAM gnuplot)
if(GNUPLOT_PROGRAM)
  sedwave_cli_case(conflict.posterior_corner_plot_drawn 3 "plot written to .*posterior_corner.png"
    invert ${OBS} --model edfm --method posterior --steps 400 --out ${CLI_OUT}/conflict_corner)
endif()
