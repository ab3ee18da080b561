# The Debian package (cpack -G DEB in a build folder; scripts/package.sh): the install rules'
# program, data, headers, static libraries and CMake package below /usr, and the Python
# package in Debian's dist-packages (component python_deb in place of python, whose folder
# below /usr is not on Debian's sys.path). Its dependencies: the shared libraries the
# program and the extension module link, as dpkg-shlibdeps reads them (Ceres, glog, yaml-cpp,
# libpng, the C++ runtime; Ceres itself is linked statically), and the Python the module was
# built for, with numpy.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME alloycolor)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "alloycolor developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "optical constants, reflectance and colour of binary metal alloys")
set(CPACK_PACKAGE_DESCRIPTION
    "Predicts n + ik, the Fresnel reflectance and the CIE colour of a binary alloy at any\n\
composition from measurements at a few, with error bars: the alloycolor program, its\n\
bundled data sets, the alloycolor Python package, and the C++ libraries with their CMake\n\
package (find_package(alloycolor); building against them needs the -dev packages\n\
suggested).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)  # the program and the extension module, as Debian ships them
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # alloycolor_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "libceres-dev, libeigen3-dev, nlohmann-json3-dev, libyaml-cpp-dev, libpng-dev, blender")
if(TARGET _alloycolor)
  math(EXPR next_minor "${Python_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}), \
python3 (<< ${Python_VERSION_MAJOR}.${next_minor}), python3-numpy")
  # Python leaves bytecode caches beside the modules it imports; prerm removes them, so
  # that dpkg -r leaves no folder behind.
  set(ALLOYCOLOR_DEB_PYTHON_PACKAGE_DIR
      ${CPACK_PACKAGING_INSTALL_PREFIX}/${ALLOYCOLOR_PYTHON_DEB_DIR}/alloycolor)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/deb/prerm.in ${PROJECT_BINARY_DIR}/deb/prerm @ONLY)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_BINARY_DIR}/deb/prerm)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
endif()

# Every component into one package, python_deb in place of python.
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
get_cmake_property(CPACK_COMPONENTS_ALL COMPONENTS)
list(REMOVE_ITEM CPACK_COMPONENTS_ALL python)
include(CPack)
