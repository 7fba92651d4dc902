# The FMU library's sources (fmu/CMakeLists.txt for linux64, fmu/cross/ for win64): the FMI
# functions and the parts of the project they run, nothing that needs HDF5 or FFTW.
# SHUDDER_SOURCE_DIR is the project's source directory.
file(GLOB FMU_CLUTCH_SOURCES CONFIGURE_DEPENDS ${SHUDDER_SOURCE_DIR}/clutch/*.cpp)
set(FMU_LIBRARY_SOURCES
  ${SHUDDER_SOURCE_DIR}/fmu/clutch_fmu.cpp
  ${FMU_CLUTCH_SOURCES}
  ${SHUDDER_SOURCE_DIR}/rig_models/thermal_task.cpp
  ${SHUDDER_SOURCE_DIR}/rig_models/realtime_clutch.cpp
  ${SHUDDER_SOURCE_DIR}/rig_models/realtime_coupling.cpp
  ${SHUDDER_SOURCE_DIR}/io/fluid_loader.cpp
  ${SHUDDER_SOURCE_DIR}/io/toml_reader.cpp)
