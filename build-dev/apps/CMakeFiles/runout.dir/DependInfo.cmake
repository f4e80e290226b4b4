
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/apps/picture_loader.cpp" "apps/CMakeFiles/runout.dir/picture_loader.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/picture_loader.cpp.o.d"
  "/work/main/apps/picture_options.cpp" "apps/CMakeFiles/runout.dir/picture_options.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/picture_options.cpp.o.d"
  "/work/main/apps/plot_command.cpp" "apps/CMakeFiles/runout.dir/plot_command.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/plot_command.cpp.o.d"
  "/work/main/apps/prepare.cpp" "apps/CMakeFiles/runout.dir/prepare.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/prepare.cpp.o.d"
  "/work/main/apps/run_command.cpp" "apps/CMakeFiles/runout.dir/run_command.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/run_command.cpp.o.d"
  "/work/main/apps/run_folder.cpp" "apps/CMakeFiles/runout.dir/run_folder.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/run_folder.cpp.o.d"
  "/work/main/apps/runout.cpp" "apps/CMakeFiles/runout.dir/runout.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/runout.cpp.o.d"
  "/work/main/apps/study_command.cpp" "apps/CMakeFiles/runout.dir/study_command.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/study_command.cpp.o.d"
  "/work/main/apps/sweep_command.cpp" "apps/CMakeFiles/runout.dir/sweep_command.cpp.o" "gcc" "apps/CMakeFiles/runout.dir/sweep_command.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-dev/core/CMakeFiles/runout_core.dir/DependInfo.cmake"
  "/work/main/build-dev/core/io/CMakeFiles/runout_io.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
