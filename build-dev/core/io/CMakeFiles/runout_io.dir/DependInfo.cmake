
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/core/io/src/files.cpp" "core/io/CMakeFiles/runout_io.dir/src/files.cpp.o" "gcc" "core/io/CMakeFiles/runout_io.dir/src/files.cpp.o.d"
  "/work/main/core/io/src/outputs.cpp" "core/io/CMakeFiles/runout_io.dir/src/outputs.cpp.o" "gcc" "core/io/CMakeFiles/runout_io.dir/src/outputs.cpp.o.d"
  "/work/main/core/io/src/scene_file.cpp" "core/io/CMakeFiles/runout_io.dir/src/scene_file.cpp.o" "gcc" "core/io/CMakeFiles/runout_io.dir/src/scene_file.cpp.o.d"
  "/work/main/core/io/src/sweep_file.cpp" "core/io/CMakeFiles/runout_io.dir/src/sweep_file.cpp.o" "gcc" "core/io/CMakeFiles/runout_io.dir/src/sweep_file.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-dev/core/CMakeFiles/runout_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
