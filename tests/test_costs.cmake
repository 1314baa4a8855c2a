# Read by ctest (tests/CMakeLists.txt adds it after the tests gtest_discover_tests found): the
# seconds the longest tests took in a clean-clone `.ci/run` (2026-11-27, 2-core machine), as each
# test's COST. On a clean clone ctest has no timings of its own yet, and with COST it starts the
# costliest first, so that no minute-long test begins last while the other core idles: the
# sanitize half had run 700 test-seconds in 424 s on two cores, its longest test (150 s) among
# the last to start. The figures only order the tests; a test's timeout is its own.
if(TEM_TESTS_SANITIZED)
  # 2026-12-01, with Newton the default solver.
  set(tem_test_costs
      MeshApproxTree.MovingPlanesLowersTheHullsAndKeepsTheSolid 72
      SemmNewton.PyramidOfCubesStandsOnASupernodalFactorisation 64
      SubSteps.ResumeAndThreadsGiveTheSameBitsWhileBodiesComeAndGo 45
      SubStepCount.TurningDrumsWorkIsAllCounted 41
      Processes.ResumeAndThreadsGiveTheSameBytesWhileBodiesComeAndGo 39
      Cli.ThreadsGiveBitIdenticalResults 35
      SimulationApi.CheckpointResumesBitForBit 31
      Resume.RefusesAMeshFileChangedSinceTheCheckpoint 27
      MeshApprox.ConvexMeshIsItsHull 25
      SimulationApi.SameHashAsTemRun 25
      Processes.ApiCheckpointResumesThePopulation 24
      SubStepCount.ResumeAndThreadsKeepTheBits 21
      Processes.InletCopiesInsideACupStartClearOfEverything 20
      BlockManifold.NoPairWithinTheMarginIsMissed 16
      MeshApprox.LIsTwoBoxes 14
      Resume.RefusesWhatItCannotContinue 12
      Resume.AFinishedRunCanBeExtended 12
      Resume.AfterAKillTheResultIsBitIdentical 12)
else()
  set(tem_test_costs
      PhysicsScene.MeshStaplePourComesToRest 61
      PhysicsScene.DefaultRingAndColumnComeToRest 32
      PhysicsScene.NewtonPourOfAHundredCoinsSleeps 12
      PhysicsScene.NewtonPourWithACoinBalancedOnALineSleeps 12
      MeshApprox.TorusBlocksAreDisjointAndKeepTheHole 26
      MeshApprox.BlocksCoverTheMesh 17
      MeshApprox.MaxBlocksIsRespected 13
      MeshApprox.SameBlocksEveryRunAndThreadCount 12
      MeshCommand.JsonGivesOverCoverageAndHausdorffInPercent 8)
  if(TEM_TESTS_MPI)
    list(APPEND tem_test_costs MpiRun.semm 29 MpiRun.semm_resume 23)
  endif()
endif()
list(LENGTH tem_test_costs tem_test_cost_count)
math(EXPR tem_test_cost_last "${tem_test_cost_count} - 1")
foreach(i RANGE 0 ${tem_test_cost_last} 2)
  math(EXPR j "${i} + 1")
  list(GET tem_test_costs ${i} name)
  list(GET tem_test_costs ${j} cost)
  set_tests_properties(${name} PROPERTIES COST ${cost})
endforeach()
