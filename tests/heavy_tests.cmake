# Tests labelled `heavy`, which the sanitizer job (`ctest --preset asan`) leaves out; the release
# suite (`ctest --preset release`, the README's command) runs them all.
#
# Why: the sanitizers instrument the project's host code. These tests spend 12 s or more on
# lavapipe (not instrumented) drawing pictures whose host code paths the lighter tests already
# take: under ASan they doubled the job's time and took CI past its 90 minutes. Each group of
# tests keeps at least one member in the sanitizer job (its cheapest, or the one whose host path
# matters most to memory: the soak, the viewer's resize storm and lost device, the lost-device
# command, `planet render`, a video, the bench plot). Except Seeds/EarthTargets: statistics of
# 2048x1024 heightmaps, 200 s each under ASan, whose code the TerrainStatistics.* tests and
# Seeds/MarsStructure run on smaller grids.
#
# ctest includes this file after the discovered tests (tests/CMakeLists.txt). A name that is not a
# test is ignored by ctest: the unit test HeavyTestList.NamesTestsThatExist catches stale names.
# LABELS replaces the test's labels, so each list keeps its group's label.
function(planet_label_heavy label)
  foreach(name IN LISTS ARGN)
    set_tests_properties("${name}" PROPERTIES LABELS "${label};heavy")
  endforeach()
endfunction()

planet_label_heavy(unit
  Seeds/EarthTargets.HoldAtThisSeed/0
  Seeds/EarthTargets.HoldAtThisSeed/1
  Seeds/EarthTargets.HoldAtThisSeed/2
  Seeds/EarthTargets.HoldAtThisSeed/3
  Seeds/EarthTargets.HoldAtThisSeed/4
)

planet_label_heavy(gpu
  TerrainGpu.SpecializedVertexHeightsMatchTheCpuForEveryTypeAndHash
  PatchTexturesGpu.UpdatesRebuildOnlyWhatMoved
  ReliefCubeGpu.FromOrbitWithoutPatchesTheCoastFollowsTheTerrainNotTheMesh
  ReliefCubeGpu.FromOrbitTheCoastIsSharpAtEveryQuality
  TerrainRender.VertexHeightsMatchTheDoubleReferenceAtTheirOctaveBudget
  TerrainRender.DrawnSurfaceDoesNotSwimWhenTheCameraMoves
  TerrainRender.HeightsAreNotRecomputedWhenNothingMoved
  TerrainRender.FrustumCullingDrawsTheSamePictureWithFewerTriangles
  TerrainRender.ShadingWithoutWhatTheViewCannotShowDrawsTheSamePicture
  TerrainRender.GroundBelowTheRadiusSphereIsDrawnToTheHorizon
  TerrainRender.SameInputsGiveIdenticalImagesAndSeedsChangeThePlanet
  TerrainRender.PatchLevelsMovedStripByStripDrawWhatAWholeBuildDraws
  TerrainRender.APatchBudgetSpreadsNewLevelsOverFramesAndEndsWithTheSamePicture
  TerrainRender.TwoMetresAboveTheGroundVerticesAreDenserThanHalfAMetre
  TerrainRender.FrozenLodKeepsTheMeshAndDrawsItFromTheMovedCamera
  TerrainRender.TogglesDrawWhatTheSettingsWouldHave
  TerrainRender.GoldenImages
  SkyRender.HdrFrameIsFiniteEverywhere
  SkyRender.SpaceIsBlackWithStars
  SkyRender.SeaLooksTheSameWithoutPatchTextures
  SkyRender.CloudsAreSeenFromAboveAndBelowAndDriftWithTime
  SkyRender.TablesSkyMatchesTheReferenceMarch
  SkyRender.HalfResolutionCloudsMatchFullResolutionAndStayOffSilhouettes
  SkyRender.SkyViewTableMatchesCpuReference
  SkyRender.MarsSkyIsButterscotchByDayAndBlueAroundTheSettingSun
  RingHaze.ARingInFrontOfTheDiscIsNotHazedByTheAirBehindIt
  RingHaze.ARingBehindTheLimbIsDimmedByTheGrazingPathsTransmittance
  RingHaze.RingsInADaytimeSkyAreSeenThroughItsAir
  SceneRender.ABodyFarFromTheOriginLooksAsItDoesNearIt
  SceneRender.ABodyTwiceAsFarFromTheSunGetsAQuarterOfTheLight
  SceneRender.ANearerBodyHidesAFartherOneAndTheRingsShowAroundIt
  SceneRender.AFarAtmosphereIsComposedAndTheSunIsDrawnOnce
  HeightSources.VertexShaderAndCpuHeightsDrawTheComputePicture
  HeightSources.EachDrawingPassIsTimedInItsOwnScope
  HeightSources.TheVertexShaderDrawsTheSameSeaAndLand
  FramesInFlight.TwoSlotsDrawWhatOneFrameAtATimeDraws
  CityLightsGpu.NightSideLightsAreOnLandAndNoneOverSeaOrIce
  CityLightsGpu.ToggleSwitchesThePipelineAndMatchesFreshRenderers
  GroundMaterialGpu.GroundAtTwoMetresHasDetailAtTheScaleOfStones
  GroundMaterialGpu.DetailDoesNotShimmerWhenTheCameraMovesOneCentimetre
  GroundMaterialGpu.SteepSlopesAreRock
  ColorSchemeGpu.TurbulenceDrawsOnlyBlackToRed
  ColorSchemeGpu.PolarCapsWhitenThePolesOfAnyScheme
  NoiseErosionGpu.TheTerrainPassEvaluatesTheErosionLayers
  NoiseErosionGpu.OctaveLimitingKeepsTheSurfaceStillAsForTheOtherTypes
  CloudShapes.BaseOfAThickCloudIsDarkerThanItsTop
  CloudShapes.NoBrightSpecksAtDistance
  ExposureGpu.AutoExposureBringsTwilightAndNightIntoView
  ExposureGpu.CityLightsKeepTheNightInView
  ExposureGpu.CityLightsFromOrbitAreOrangeNotBlownOut
  ExposureGpu.StarsStayVisibleAndUnsaturatedAtNight
  ExposureGpu.AutoExposureRenderIsTheSameEveryTime
  ExposureGpu.ViewerAdaptationFollowsTheCpuStep
  EclipseGpu.GroundInTheMoonsUmbraIsDarkAndOutsideItLit
  EclipseGpu.TheMoonInTerrasUmbraIsDark
  EclipseGpu.AMoonsShadowFallsOnTheRings
)

planet_label_heavy(cli
  Cli.RenderSceneFromTheMoonLooksAtTerra
  Cli.ValidatePassesAndWritesJson
  Cli.BenchReportsEveryFieldWithConsistentTimesAndCompareRatios
  Cli.BenchLeadInFramesRebuildWhatARealTimeFrameRebuilds
  Cli.NoLightsLeavesOutTheCityLights
  DeviceFaults.AMemoryLimitTheWorkFitsInChangesNothing
  Determinism.TwoProcessesRenderTheSameBytesAndAnotherSeedAnotherPlanet
  VideoCli.AFlightIsAnMp4OfTheFramesAskedAndTheSameEveryRun
  VideoCli.ASceneFlightOverAnotherBodyIsAWebm
  ExposureCli.RenderAutoIsDeterministicAndSaysItsExposure
)

planet_label_heavy(viewer
  Viewer.DescentPathDrawsThePlanetWithoutValidationMessagesOrLeaks
  Viewer.TravelsFromTheMoonToTerraInAScene
  Viewer.AFrameAfterALoopEqualsASingleFrameAtTheSamePose
)
