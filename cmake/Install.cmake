# `cmake --install BUILD [--prefix P]`: the two programs, the standard library, the domains (their .cbtl files,
# scenes and external simulators, in the same layout, so every relative `world`/`simulator`/import path still
# resolves) and the documentation. tests/integration/install.sh installs into a temporary prefix and runs every
# domain from there.
include(GNUInstallDirs)
foreach(_program IN ITEMS cbtl cbtlc)
  if(TARGET ${_program})
    install(TARGETS ${_program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/stdlib/std DESTINATION ${CMAKE_INSTALL_DATADIR}/cbtl/stdlib
        FILES_MATCHING PATTERN "*.cbtl")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/domains/ DESTINATION ${CMAKE_INSTALL_DATADIR}/cbtl/domains
        FILES_MATCHING PATTERN "*.cbtl" PATTERN "*.xml" PATTERN "*.py" PATTERN "*.stl" PATTERN "*.obj" PATTERN "*.png")
install(PROGRAMS ${PROJECT_SOURCE_DIR}/domains/coffee/coffee_sim.py DESTINATION ${CMAKE_INSTALL_DATADIR}/cbtl/domains/coffee)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
