# Command-line cases of `sedwave interface` (docs/interface.md): bad scene values are refused naming
# file, line, key and accepted range; a tiny scene runs and closes its energy balance. Files under
# data/interface/.
set(INTERFACE_DATA ${CLI_DATA}/interface)
set(INTERFACE_OUT ${CLI_OUT}/interface)
file(MAKE_DIRECTORY ${INTERFACE_OUT})
sedwave_cli_case(interface.bad_poisson 1 [=[bad_poisson\.toml:4: key 'plate\.poisson_ratio' = 0\.6: accepted range \[0, 0\.5\)]=] interface ${INTERFACE_DATA}/bad_poisson.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.misspelt_key 1 [=[misspelt_key\.toml:10: key 'packing\.colums': unknown key]=] interface ${INTERFACE_DATA}/misspelt_key.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.packing_wider_than_plate 1 [=[packing_too_wide\.toml:[0-9]+: \[packing\]: 'x_offset' \(default\): the packing \(0\.1525 m wide\) must lie over the plate \(0\.024 m\)]=] interface ${INTERFACE_DATA}/packing_too_wide.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.output_over_scene 2 [=[--out: output .*would overwrite the input]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_DATA}/tiny.toml)
sedwave_cli_case(interface.tiny_run 0 [=[largest share in the plate [0-9.]+. energy balance within [0-9.]+e-0[6-9] of the input]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_OUT}/tiny.h5)
sedwave_cli_case(interface.precompression_needs_a_clamped_edge 1 [=[unsupported_precompression\.toml:13: key 'packing\.precompression': a static load needs a clamped plate edge]=] interface ${INTERFACE_DATA}/unsupported_precompression.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.direct_strike 0 [=[direct strike on the plate's edge over x = 0\.00575 \.\. 0\.02075 m with the energy of 3 beads]=] interface ${INTERFACE_DATA}/tiny.toml --direct --out ${INTERFACE_OUT}/direct.h5)
