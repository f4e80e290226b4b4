
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/core/src/checkpoint.cpp" "core/CMakeFiles/runout_core.dir/src/checkpoint.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/checkpoint.cpp.o.d"
  "/work/main/core/src/derive.cpp" "core/CMakeFiles/runout_core.dir/src/derive.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/derive.cpp.o.d"
  "/work/main/core/src/measure.cpp" "core/CMakeFiles/runout_core.dir/src/measure.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/measure.cpp.o.d"
  "/work/main/core/src/neighbor_list.cpp" "core/CMakeFiles/runout_core.dir/src/neighbor_list.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/neighbor_list.cpp.o.d"
  "/work/main/core/src/run.cpp" "core/CMakeFiles/runout_core.dir/src/run.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/run.cpp.o.d"
  "/work/main/core/src/setup.cpp" "core/CMakeFiles/runout_core.dir/src/setup.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/setup.cpp.o.d"
  "/work/main/core/src/walls.cpp" "core/CMakeFiles/runout_core.dir/src/walls.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/walls.cpp.o.d"
  "/work/main/core/src/world.cpp" "core/CMakeFiles/runout_core.dir/src/world.cpp.o" "gcc" "core/CMakeFiles/runout_core.dir/src/world.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
