# Layers that enforce the dependency order (docs/ARCHITECTURE.md). Sources include headers by layer name
# ("engine/simulation.hpp"); a layer's include directory holds a link named after the layer to its folder and
# nothing else, so a target sees the headers of exactly the layers it links, and an include of any other
# layer does not compile. The links live in the build tree: ${CMAKE_BINARY_DIR}/layers/<layer>/<name>.

# The include directory under which `name/...` names the files of `folder` (relative to the project).
function(lpsim_layer_include out name folder)
  set(root ${CMAKE_BINARY_DIR}/layers/${name})
  file(MAKE_DIRECTORY ${root})
  if(NOT EXISTS ${root}/${name})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${root}/${name} SYMBOLIC)
  endif()
  set(${out} ${root} PARENT_SCOPE)
endfunction()

# A header-only layer: an INTERFACE target whose users see `name/...`.
function(lpsim_layer_headers target name folder)
  lpsim_layer_include(dir ${name} ${folder})
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE ${dir})
endfunction()

# A layer with sources: a static library of folder/*.cpp whose users (and itself) see `name/...`.
function(lpsim_layer target name folder)
  lpsim_layer_include(dir ${name} ${folder})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${folder}/*.cpp)
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC ${dir})
endfunction()
