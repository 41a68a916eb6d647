#!/usr/bin/env bash
# Writes samples/terrain/hill_wgs84.tif: the project's hill (samples/terrain/hill.asc) as a
# GeoTIFF in geographic degrees (WGS 84), Float32, tiled and compressed, placed in the
# Huangshan range, the way SRTM and Copernicus tiles come: shanshui converts its 0.00005
# degree cells to metres at its centre latitude. Needs gdal-bin (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
gdal_translate -q -of GTiff -a_srs EPSG:4326 -a_ullr 118.150 30.140 118.158 30.132 -ot Float32 \
  -co COMPRESS=DEFLATE -co PREDICTOR=3 -co TILED=YES -co BLOCKXSIZE=64 -co BLOCKYSIZE=64 \
  samples/terrain/hill.asc samples/terrain/hill_wgs84.tif
echo "wrote samples/terrain/hill_wgs84.tif"
