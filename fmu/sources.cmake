# The FMU library's sources (fmu/CMakeLists.txt for linux64, fmu/cross/ for win64): the FMI
# functions and the parts of the project they run, nothing that needs HDF5 or FFTW.
# SHUDDER_SOURCE_DIR is the project's source directory.
file(GLOB FMU_CLUTCH_SOURCES CONFIGURE_DEPENDS ${SHUDDER_SOURCE_DIR}/clutch/*.cpp)
set(FMU_LIBRARY_SOURCES
  ${SHUDDER_SOURCE_DIR}/fmu/clutch_fmu.cpp
  ${SHUDDER_SOURCE_DIR}/fmu/fmi2_functions.cpp
  ${FMU_CLUTCH_SOURCES}
  ${SHUDDER_SOURCE_DIR}/rig_models/thermal_task.cpp
  ${SHUDDER_SOURCE_DIR}/rig_models/realtime_clutch.cpp
  ${SHUDDER_SOURCE_DIR}/rig_models/realtime_coupling.cpp
  ${SHUDDER_SOURCE_DIR}/io/fluid_loader.cpp
  ${SHUDDER_SOURCE_DIR}/io/toml_reader.cpp)

# The network FMU's library: the network's components, their builder and stepper, the scenario
# reader, nothing that needs HDF5 or FFTW (no spectra, no verdicts: the FMU only steps).
file(GLOB FMU_DYNAMICS_SOURCES CONFIGURE_DEPENDS ${SHUDDER_SOURCE_DIR}/dynamics/*.cpp)
set(FMU_NETWORK_SOURCES
  ${SHUDDER_SOURCE_DIR}/fmu/network_fmu.cpp
  ${SHUDDER_SOURCE_DIR}/fmu/network_variables.cpp
  ${SHUDDER_SOURCE_DIR}/fmu/fmi2_functions.cpp
  ${FMU_CLUTCH_SOURCES}
  ${FMU_DYNAMICS_SOURCES})
foreach(source
    components/signal components/network_builder components/network_checks components/network_channels
    components/network_stepper components/lash_shaft components/plain_friction components/haldex_control
    components/clutch_contact components/drive_cycle components/multirate_clutch rig_models/effect_registry components/pack_oil
    components/haldex_coupling_law components/haldex_hydraulics components/haldex_controller components/engine
    components/engine_pulsation components/motor_ripple components/tyre
    io/network_scenario io/network_components io/scenario io/haldex_tables io/fluid_loader io/toml_reader)
  list(APPEND FMU_NETWORK_SOURCES ${SHUDDER_SOURCE_DIR}/${source}.cpp)
endforeach()
