// Import speed of the foundation stages on the shipped real DEM. Compare rows of one run
// with each other (this machine is shared); absolute times are only indicative.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/terrain/terrain_mesh.h"

namespace {

using namespace shanshui;
const std::filesystem::path kDem = std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/terrain/mount_st_helens.dem";

void BM_LoadUsgsDem(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(terrain::loadHeightfield(kDem));
}
BENCHMARK(BM_LoadUsgsDem)->Unit(benchmark::kMillisecond);

void BM_HeightfieldToMesh(benchmark::State& state) {
  const terrain::Heightfield h = terrain::loadHeightfield(kDem);
  terrain::TerrainMeshOptions o;
  o.step = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(terrain::heightfieldToMesh(h, o));
}
BENCHMARK(BM_HeightfieldToMesh)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_RepairTerrainMesh(benchmark::State& state) {
  terrain::TerrainMeshOptions o;
  o.step = static_cast<int>(state.range(0));
  const mesh::Mesh m = terrain::heightfieldToMesh(terrain::loadHeightfield(kDem), o);
  mesh::PolygonSoup soup;
  soup.positions = m.positions;
  for (const auto& t : m.triangles) soup.faces.push_back({t.x, t.y, t.z});
  for (auto _ : state) benchmark::DoNotOptimize(mesh::repairMesh(soup, {}, nullptr));
  state.counters["triangles"] = static_cast<double>(m.triangleCount());
}
BENCHMARK(BM_RepairTerrainMesh)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_WriteReadObj(benchmark::State& state) {
  terrain::TerrainMeshOptions o;
  o.step = 2;
  const mesh::Mesh m = terrain::heightfieldToMesh(terrain::loadHeightfield(kDem), o);
  const auto path = std::filesystem::temp_directory_path() / "shanshui_bench.obj";
  for (auto _ : state) {
    mesh::writeMesh(m, path);
    benchmark::DoNotOptimize(mesh::readPolygonSoup(path));
  }
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteReadObj)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
