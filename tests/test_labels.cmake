# Included by ctest (TEST_INCLUDE_FILES) after the tests gtest_discover_tests found, whose names
# it lists in relief_<module>_tests_TESTS: each test gets its module's label and one of
#   tools     runs an external program: netconvert (any build with the SUMO output), sumo,
#             duarouter, xmllint, blender, bash (the CLI and packaging scripts); it may also
#             read ../shared/data
#   realdata  reads ../shared/data and runs no external program
#   unit      neither: the libraries only
# by the name patterns below (regular expressions on Suite.Test). tools/check-labels.sh proves
# them: unit tests pass with no data and no programs, realdata tests with no programs.
set(relief_tools_tests
  # builds with the SUMO output (netconvert)
  "^Build\\.(SyntheticPlaneHasExactGrades|CallersSignalledJunctionsJoinTheOsmOnes|PotreroWithReferenceDem)$"
  "^Build\\.BrokenDemWithVoidsIsFilledAndReported$"
  "^(Corpus|Fuzz|Regions|Sumo)\\."
  # region tiles merged (the merge builds the region's SUMO network: netconvert)
  "^Tiles\\.(OldTownMergesLikeTheWholeBuild|AStructureChainLongerThanTheHaloMergesLikeTheWholeBuild)$"
  "^Tiles\\.OldTownFarFromTheFrameOriginMergesLikeTheWholeBuild$"
  "^Tiles\\.(ARoadSplitBeyondTheWindowIsOwnedByTheTileOfItsMidpoint|TilesHoldWhatTheirNeighboursFittedSoTheyMeetWhereWindowsSeeTooLittle)$"
  "^Tiles\\.AMountainRangesRoadsTakeTheirOwnersHeightsAcrossTheTileLines$"
  "^TilesRealData\\."
  # a relief build with the SUMO output, then SUMO in this process (libsumo)
  "^(Cosim|CosimRealData|SumoSession)\\."
  # a relief build, then randomTrips.py, duarouter, routeSampler.py and SUMO
  "^Demand\\."
  # xmllint, python3 (xmlschema, the HTML parse), blender
  "^OpenDriveWriter\\.(ValidatesAgainstTheOpenDrive1[78]Schema|WritesOpenDrive14WithWholeSpeedsAndNoOffset)$"
  "^ReportHtml\\.(OpenDriveFiguresAppearWhenAFileWasWritten|ParsesAsXmlWithOnePlotPerProfileHistogramAndMaps)$"
  "^MeshWriter\\.BlenderImportsFbxGlbAndObjInMetresZUp$"
  # python3 with Open3D
  "^Lidar\\.PointCloudsOpenInOpen3d$")
set(relief_realdata_tests
  "^(DemSamplerRealData|InspectDemRealData|ProfileFitRealData)\\."
  "^(NetworkBuilder|OsmReader)\\.(PotreroRealData|NortheastRealData)$"
  "^OsmReader\\.(TruncatedRealGzipThrowsInvalidInput|PotreroAsPbfReadsLikeGzip)$"
  "^Build\\.(FailedRunLeavesNoOutputs|PotreroIdwDiffersFromBilinear)$"
  "^Info\\.DescribesPotreroWithoutWriting$"
  "^TilesTerrain\\."
  "^TilePlan\\.TakesTheFrameCentreItIsGiven$"
  "^MeshPipeline\\.(PotreroTilesAddUpToTheScene|PotreroCarlaPackageHoldsTheFilesWritten)$"
  "^MeshPipeline\\.PotreroCarlaLargeMapFillsTheTileGrid$")

foreach(module IN LISTS relief_test_modules)
  foreach(test IN LISTS relief_${module}_tests_TESTS)
    set(kind unit)
    foreach(pattern IN LISTS relief_realdata_tests)
      if(test MATCHES "${pattern}")
        set(kind realdata)
      endif()
    endforeach()
    foreach(pattern IN LISTS relief_tools_tests)
      if(test MATCHES "${pattern}")
        set(kind tools)
      endif()
    endforeach()
    set_tests_properties("${test}" PROPERTIES LABELS "${module};${kind}")
  endforeach()
endforeach()
