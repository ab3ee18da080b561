# Zips the Blender add-on (run by blender/CMakeLists.txt as cmake -P THIS):
#   -DSOURCE_DIR=blender/alloycolor_material  -DMANIFEST=blender/blender_manifest.toml.in
#   -DPROJECT_VERSION=x.y.z  -DSTAGE_DIR=scratch folder  -DZIP=out.zip
# The zip holds one folder, alloycolor_material/, as Blender's "Install add-on" (3.4 and
# later) takes it, with blender_manifest.toml inside, as 4.2's "Install from Disk" takes an
# extension. Both carry the project's version: bl_info's "version" tuple is rewritten.
foreach(var SOURCE_DIR MANIFEST PROJECT_VERSION STAGE_DIR ZIP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "BlenderAddonZip.cmake: -D${var}= is missing")
  endif()
endforeach()
get_filename_component(name ${SOURCE_DIR} NAME)
set(folder ${STAGE_DIR}/${name})
file(REMOVE_RECURSE ${STAGE_DIR})
file(MAKE_DIRECTORY ${folder})
file(GLOB sources RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/*.py)
foreach(source ${sources})
  file(READ ${SOURCE_DIR}/${source} text)
  if(source STREQUAL "__init__.py")
    set(pattern "\"version\": \\([0-9]+, [0-9]+, [0-9]+\\)")
    string(REGEX MATCHALL "${pattern}" found "${text}")
    list(LENGTH found count)
    if(NOT count EQUAL 1)
      message(FATAL_ERROR "${SOURCE_DIR}/__init__.py: expected one bl_info \"version\": "
                          "(a, b, c), found ${count}")
    endif()
    string(REPLACE "." ", " tuple ${PROJECT_VERSION})
    string(REGEX REPLACE "${pattern}" "\"version\": (${tuple})" text "${text}")
  endif()
  file(WRITE ${folder}/${source} "${text}")
endforeach()
configure_file(${MANIFEST} ${folder}/blender_manifest.toml @ONLY)
file(REMOVE ${ZIP})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip ${name}
                WORKING_DIRECTORY ${STAGE_DIR} COMMAND_ERROR_IS_FATAL ANY)
