# Test inputs that are not in the repository:
#  - CGAL's test meshes from Debian's libcgal-demo (installed by scripts/setup.sh), extracted
#    into the build tree;
#  - the real DEMs and textures under SHANSHUI_DATA_DIR (../shared/data by default).
set(SHANSHUI_CGAL_DATA_ARCHIVE "/usr/share/doc/libcgal-dev/data.tar.gz" CACHE FILEPATH
    "CGAL's test data archive (Debian package libcgal-demo)")
set(SHANSHUI_TEST_MESH_DIR "${PROJECT_BINARY_DIR}/test-data/cgal")
set(cgal_meshes three_peaks.off elephant-with-holes.off holes.off lion.off blobby_3cc.off
    triceratops.off anchor.off degtri_sliding.off oblong-shuffled.off cube-ouvert.off bear.off
    cube_quad.off cross_quad.off cow.off elk.off camel.off armadillo.off bunny00.off)
if(EXISTS "${SHANSHUI_CGAL_DATA_ARCHIVE}" AND NOT EXISTS "${SHANSHUI_TEST_MESH_DIR}/bunny00.off")
  set(patterns "")
  foreach(m IN LISTS cgal_meshes)
    list(APPEND patterns "data/meshes/${m}")
  endforeach()
  file(ARCHIVE_EXTRACT INPUT "${SHANSHUI_CGAL_DATA_ARCHIVE}" DESTINATION "${PROJECT_BINARY_DIR}/test-data/tmp"
       PATTERNS ${patterns})
  file(MAKE_DIRECTORY "${SHANSHUI_TEST_MESH_DIR}")
  foreach(m IN LISTS cgal_meshes)
    if(EXISTS "${PROJECT_BINARY_DIR}/test-data/tmp/data/meshes/${m}")
      file(RENAME "${PROJECT_BINARY_DIR}/test-data/tmp/data/meshes/${m}" "${SHANSHUI_TEST_MESH_DIR}/${m}")
    endif()
  endforeach()
  file(REMOVE_RECURSE "${PROJECT_BINARY_DIR}/test-data/tmp")
endif()
if(NOT EXISTS "${SHANSHUI_TEST_MESH_DIR}/bunny00.off")
  message(WARNING "CGAL test meshes not found (${SHANSHUI_CGAL_DATA_ARCHIVE}); run scripts/setup.sh")
endif()
get_filename_component(SHANSHUI_DATA_DIR_ABS "${SHANSHUI_DATA_DIR}" ABSOLUTE)
if(NOT EXISTS "${SHANSHUI_DATA_DIR_ABS}/terrain")
  message(WARNING "SHANSHUI_DATA_DIR=${SHANSHUI_DATA_DIR_ABS} has no terrain/: tests on the shared data will be skipped")
endif()

# Paths handed to every test binary.
function(shanshui_test_paths target)
  target_compile_definitions(${target} PRIVATE
    SHANSHUI_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SHANSHUI_BIN_DIR="${PROJECT_BINARY_DIR}/bin"
    SHANSHUI_DATA_DIR="${SHANSHUI_DATA_DIR_ABS}"
    SHANSHUI_TEST_MESH_DIR="${SHANSHUI_TEST_MESH_DIR}")
endfunction()
