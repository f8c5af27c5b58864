# Debian 12 packages; see tools/setup.sh for the list that installs them.
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(OpenImageIO REQUIRED)
find_package(glm REQUIRED)
# Embree 3 (target `embree`, no namespace) for the path tracer; the CLI reports its version.
find_package(embree 3 REQUIRED)
# libpng directly for PNG textures: OpenImageIO's PNG reader lets libpng print on standard error.
find_package(PNG REQUIRED)

# Debian's OpenImageIO target lists /usr/include/opencv4, which exists only with libopencv-dev;
# CMake refuses non-existent include paths, so keep only the ones that exist.
foreach(target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${target})
    get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(dirs)
      set(existing "")
      foreach(dir IN LISTS dirs)
        if(EXISTS "${dir}")
          list(APPEND existing "${dir}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${existing}")
    endif()
  endif()
endforeach()
