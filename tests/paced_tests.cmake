# Read by ctest after the discovered tests' include files (tests/CMakeLists.txt): the tests that
# step at the wall clock's pace run with nothing beside them — the emulated rig in the loop, and
# the replay window that plays a recording to its end in real time before its keys are pressed
# (beside the seeded long cut runs it once took 88 s and failed).
set_tests_properties(RigSession.TheRigScenePerformsTheWholeAppendectomyThroughTheEmulatedRig
                     ReplayTimeline.TheNKeyJumpsToEachErrorInTheWindow PROPERTIES RUN_SERIAL TRUE)
