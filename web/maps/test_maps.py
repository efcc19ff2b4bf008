"""Tests the slippy map page (web/maps/dist) in headless Chromium against `motif tiles serve`.

Usage: python3 web/maps/test_maps.py [--screenshots DIR] [--motif target/release/motif]

Starts the tile server on a free port over the real Helsinki extract (data/real/maps), serves
the built page, and with real input events pans the map (a mouse drag), zooms in (the zoom
button and the mouse wheel) and switches to the plain layer in the layers control. Checks that
tiles load from the server at every step, that none fails, that the plain layer's tiles come from
/plain/, and that the browser console has no errors; saves a screenshot per step. Needs Debian's
`chromium` and `chromium-driver` and `pip install selenium`.
"""

import argparse
import pathlib
import subprocess
import sys
import tempfile

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE.parent))
from test_page import browser, serve, wait_for  # noqa: E402  (the playground test's helpers)


def loaded(driver):
    return driver.execute_script("return window.motifMap ? [window.motifMap.loaded, window.motifMap.failed] : [0, 0]")


def wait_for_more_tiles(driver, after, what):
    wait_for(driver, f"return window.motifMap && window.motifMap.loaded > {after}", 120, what)
    # Then until the view has settled: the shown layer loads nothing more.
    settled = "const m = window.motifMap; return !m.layers[m.current].isLoading();"
    try:
        wait_for(driver, settled, 120, f"{what}: every tile in view")
    except AssertionError:
        pending = driver.execute_script(
            "const l = window.motifMap.layers[window.motifMap.current];"
            "return Object.values(l._tiles).filter(t => !t.loaded).map(t => t.el.src + ' ' + t.el.complete)"
        )
        raise AssertionError(f"{what}: tiles never loaded: {pending[:6]}")
    count, failed = loaded(driver)
    assert failed == 0, f"{what}: {failed} tiles failed"
    return count


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--screenshots", default=None)
    parser.add_argument("--motif", default=str(ROOT / "target" / "release" / "motif"))
    arguments = parser.parse_args()
    dist = HERE / "dist"
    if not (dist / "index.html").is_file():
        sys.exit("web/maps/dist is not built: run web/maps/build.sh first")
    shots = pathlib.Path(arguments.screenshots or tempfile.mkdtemp(prefix="motif-maps-"))
    shots.mkdir(parents=True, exist_ok=True)
    cache = tempfile.mkdtemp(prefix="motif-tiles-cache-")
    tiles = subprocess.Popen(
        [arguments.motif, "--quiet", "tiles", "serve", "--map", str(ROOT / "data/real/maps/Helsinki.osm.pbf")]
        + ["--port", "0", "--cache-dir", cache],
        stdout=subprocess.PIPE,
        text=True,
    )
    page = serve(dist)
    driver = None
    try:
        address = tiles.stdout.readline().strip().rstrip("/")
        assert address.startswith("http://127.0.0.1:"), address
        driver = browser()
        driver.set_window_size(1000, 800)
        driver.get(f"http://127.0.0.1:{page.server_address[1]}/index.html?tiles={address}")
        count = wait_for_more_tiles(driver, 0, "the first view")
        driver.save_screenshot(str(shots / "1-stylized.png"))
        map_element = driver.find_element(By.ID, "map")
        # Pan: a real mouse drag across the map.
        ActionChains(driver).move_to_element(map_element).click_and_hold().move_by_offset(60, 40).move_by_offset(
            60, 40
        ).release().perform()
        count = wait_for_more_tiles(driver, count, "tiles after the pan")
        driver.save_screenshot(str(shots / "2-panned.png"))
        # Zoom: the zoom-in button, then the mouse wheel.
        zoom = driver.execute_script("return window.motifMap.map.getZoom()")
        driver.find_element(By.CSS_SELECTOR, ".leaflet-control-zoom-in").click()
        wait_for(driver, f"return window.motifMap.map.getZoom() === {zoom + 1}", 30, "the zoom button")
        count = wait_for_more_tiles(driver, count, "tiles after zooming in")
        ActionChains(driver).scroll_to_element(map_element).scroll_by_amount(0, -300).perform()
        wait_for(driver, f"return window.motifMap.map.getZoom() > {zoom + 1}", 30, "the mouse wheel")
        count = wait_for_more_tiles(driver, count, "tiles after the wheel")
        driver.save_screenshot(str(shots / "3-zoomed.png"))
        # Switch layers in the layers control (it opens on hover).
        control = driver.find_element(By.CSS_SELECTOR, ".leaflet-control-layers")
        ActionChains(driver).move_to_element(control).perform()
        radios = driver.find_elements(By.CSS_SELECTOR, ".leaflet-control-layers-base input")
        wait_for(driver, "return document.querySelector('.leaflet-control-layers-expanded') !== null", 10, "the control")
        radios[1].click()
        count = wait_for_more_tiles(driver, count, "the plain layer's tiles")
        sources = driver.execute_script(
            "return [...window.motifMap.layers.plain.getContainer().querySelectorAll('img.leaflet-tile-loaded')].map(t => t.src)"
        )
        assert sources and all("/plain/" in src for src in sources), sources[:3]
        driver.save_screenshot(str(shots / "4-plain.png"))
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        assert not errors, f"browser console errors: {errors}"
        print(f"maps page test passed: {count} tiles loaded, none failed; screenshots in {shots}")
    finally:
        if driver is not None:
            driver.quit()
        page.shutdown()
        tiles.terminate()
        tiles.wait(timeout=30)


if __name__ == "__main__":
    main()
