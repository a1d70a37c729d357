# Read by ctest after the discovered tests' include files (tests/CMakeLists.txt): the tests that
# step at the wall clock's pace with the emulated rig in the loop run with nothing beside them.
set_tests_properties(RigSession.TheRigScenePerformsTheWholeAppendectomyThroughTheEmulatedRig
                     PROPERTIES RUN_SERIAL TRUE)
