"""Scenarios from Python: the paper, files, TOML text, dicts and overrides; bad input raises
InvalidParameter with the command line's message, word for word."""
import re
import subprocess

import pytest

import fogradar

# One case per way the scenario reader or a check refuses a scenario (experiment/scenario.cpp,
# core/keys.hpp, the sensors' validate()): the key each names.
BAD_SCENARIOS = [
    ({"radar": {"tx_power_dbm": 99.0}}, "radar.tx_power_dbm"),                 # number range
    ({"radar": {"tx_power_dbm": "high"}}, "radar.tx_power_dbm"),               # number type
    ({"radar": {"samples_per_chirp": 2.5}}, "radar.samples_per_chirp"),        # integer type
    ({"radar": {"samples_per_chirp": 8}}, "radar.samples_per_chirp"),          # integer range
    ({"camera": {"write_roi_images": 1}}, "camera.write_roi_images"),          # boolean
    ({"radar": {"sweep_direction": "sideways"}}, "radar.sweep_direction"),     # choice
    ({"radar": {"no_such_key": 1}}, "radar.no_such_key"),                      # unknown key
    ({"no_such_section": {"a": 1}}, "no_such_section"),                        # unknown section
    ({"radar": 5}, "radar"),                                                   # not a table
    ({"radar": {"carrier_frequency_hz": 77e9}}, "radar.carrier_frequency_hz"),  # retired key
    ({"fog": {"droplets": {"diameter_m": 1e-5}}}, "fog.droplets.diameter_m"),  # takes no effect
    ({"fog": {"lwc_g_per_m3": 0.1, "visibility_m": 50.0}}, "fog.visibility_m"),  # one of a group
    ({"experiment": {"sensors": []}}, "experiment.sensors"),                   # empty name list
    ({"experiment": {"sensors": ["sonar"]}}, "experiment.sensors"),            # unknown name
    ({"experiment": {"sensors": ["radar", "radar"]}}, "experiment.sensors"),   # repeated name
    ({"lidar": {"background": 5}}, "lidar.background"),                        # table array type
    ({"lidar": {"background": [{"x0_m": 1.0, "reflectivity": 7.0}]}},
     "lidar.background[0].reflectivity"),                                      # element range
    ({"experiment": {"max_active_layers": 9}}, "experiment.max_active_layers"),  # bound by a key
    ({"radar": {"processing": {"cfar": {"training_cells": 400}}}},
     "radar.processing.cfar.training_cells"),                                        # CFAR profile
    ({"chamber": {"target_gap_m": 500.0}}, "chamber.target_gap_m"),            # radar's range
]


@pytest.mark.parametrize("mapping,key", BAD_SCENARIOS)
def test_every_bad_scenario_raises_the_command_lines_message(mapping, key, cli_error):
    text = fogradar.dict_to_toml(mapping)
    message, path, status = cli_error(text)
    assert status == 2
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Scenario.from_toml(text, source=path)
    error = raised.value
    assert isinstance(error, ValueError)
    assert str(error) == message
    assert error.key == key
    assert error.line == int(message[len(path) + 1:].split(":")[0])
    # A dict has no lines the user wrote: the same message names the source and the key alone,
    # without the line of the TOML text written from it or those of other keys.
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Scenario.from_dict(mapping, source=path)
    error = raised.value
    unlined = re.sub(r" \(line \d+\)", "", message.split(":", 2)[2])
    unlined = re.sub(r" \([^()]* at line \d+(, [^()]* at line \d+)*\)$", "", unlined)
    assert str(error) == path + ":" + unlined
    assert "line" not in str(error).replace("multiline", "")
    assert (error.key, error.line) == (key, None)


def test_a_dict_s_error_names_the_users_dotted_key():
    cases = [
        ({"radar": {"tx_power_dbm": 99.0}}, "<dict>: radar.tx_power_dbm = 99.0: must be in [-30, 50]"),
        ({"chamber": {"layers": [{"length_m": 1.0}, {"length_m": -1.0}]}},
         "<dict>: chamber.layers[1].length_m = -1.0: must be in (0, 10000]"),
        ({"chamber.layers": [{"length_m": 1.0, "fog": {"lwc_g_per_m3": -1.0}}]},
         "<dict>: chamber.layers[0].fog.lwc_g_per_m3 = -1.0: must be in [0, 100]"),
        ({"fog": {"lwc_g_per_m3": 0.1, "visibility_m": 50.0}},
         "<dict>: fog.lwc_g_per_m3 and fog.visibility_m are both given: at most one fog density of "
         "fog.lwc_g_per_m3, fog.extinction_per_km, fog.visibility_m per [fog]"),
    ]
    for mapping, message in cases:
        with pytest.raises(fogradar.InvalidParameter) as raised:
            fogradar.Scenario.from_dict(mapping)
        assert str(raised.value) == message
        assert raised.value.line is None
    # A layer's own fog, given as a dict, is that layer's fog table.
    layered = fogradar.Scenario.from_dict(
        {"chamber": {"layers": [{"length_m": 1.0, "fog": {"lwc_g_per_m3": 2.0}}]}})
    assert layered.to_dict()["chamber"]["layers"][0]["fog"]["lwc_g_per_m3"] == 2.0


def test_a_file_s_error_names_its_line_as_the_command_does(cli_error):
    text = "[radar]\ntx_power_dbm = 10.0\n\n[chamber]\nlayer_count = 0\n"
    message, path, _ = cli_error(text, "lines.toml")
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Scenario.from_file(path)
    assert str(raised.value) == message
    assert (raised.value.key, raised.value.line) == ("chamber.layer_count", 5)
    with pytest.raises(fogradar.InvalidParameter) as from_text:
        fogradar.Scenario.from_toml(text, source=path)
    assert str(from_text.value) == message


def test_a_missing_file_is_refused_naming_the_option(tmp_path):
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Scenario.from_file(tmp_path / "none.toml")
    assert raised.value.key == "--scenario" and raised.value.line is None


def test_the_paper_scenario_resolves_as_the_command_writes_it(paper_cli_run):
    assert fogradar.Scenario.paper().to_toml() == (paper_cli_run / "scenario.toml").read_text()


def test_dotted_and_nested_keys_and_files_give_the_same_scenario(tmp_path):
    nested = fogradar.Scenario.from_dict({"fog": {"lwc_g_per_m3": 0.5},
                                          "experiment": {"sensors": ["radar"]}})
    dotted = fogradar.Scenario.from_dict({"fog.lwc_g_per_m3": 0.5,
                                          "experiment.sensors": ["radar"]})
    path = tmp_path / "s.toml"
    path.write_text('[fog]\nlwc_g_per_m3 = 0.5\n[experiment]\nsensors = ["radar"]\n')
    from_file = fogradar.Scenario.from_file(path)
    assert nested.to_toml() == dotted.to_toml() == from_file.to_toml()
    assert nested.sensors == ["radar"]
    assert nested.to_dict()["fog"]["lwc_g_per_m3"] == 0.5


def test_overrides_make_a_new_scenario_and_keep_the_rest():
    base = fogradar.Scenario.from_dict({"radar.measurements_per_step": 7})
    thicker = base.with_overrides({"fog.visibility_m": 30.0, "radar.tx_power_dbm": 5.0})
    assert base.to_dict()["radar"]["tx_power_dbm"] != 5.0
    assert "extinction_per_km" in base.to_dict()["fog"]  # the paper's fog density
    resolved = thicker.to_dict()
    assert resolved["radar"]["tx_power_dbm"] == 5.0
    # Another of the fog density's keys selects itself (docs/scenario.md).
    assert resolved["fog"]["visibility_m"] == 30.0 and "extinction_per_km" not in resolved["fog"]
    assert resolved["radar"]["measurements_per_step"] == 7


def test_a_scenario_round_trips_through_its_dict():
    scenario = fogradar.Scenario.from_dict({"lidar.scans_per_step": 3, "camera.frames_per_step": 2})
    again = fogradar.Scenario.from_dict(scenario.to_dict())
    assert again.to_toml() == scenario.to_toml()


def test_the_command_s_scenario_listing_names_the_same_keys(cli):
    listed = subprocess.run([cli, "scenario"], capture_output=True, text=True, check=True).stdout
    paper = fogradar.Scenario.from_toml(listed, "fogradar scenario")
    assert paper.to_toml() == fogradar.Scenario.paper().to_toml()


def test_the_room_is_nested_tables_a_surface_false_for_none():
    room = {"chamber": {"room": {"floor": False,
                                 "left_wall": {"distance_m": 2.5, "material": "concrete"}},
                        "objects": [{"shape": "cylinder", "x_m": 3.0, "y_m": -2.0}]}}
    scenario = fogradar.Scenario.from_dict(room)
    chamber = scenario.to_dict()["chamber"]
    assert chamber["room"]["floor"] is False
    assert chamber["room"]["left_wall"] == {"material": "concrete", "distance_m": 2.5}
    assert "ceiling" not in chamber["room"] or chamber["room"]["ceiling"] is False
    assert [o["shape"] for o in chamber["objects"]] == ["cylinder"]
    assert fogradar.Scenario.from_dict(scenario.to_dict()).to_toml() == scenario.to_toml()
    emptied = scenario.with_overrides({"chamber.objects": [], "chamber.room.left_wall": False})
    assert emptied.to_dict()["chamber"]["objects"] == []
    assert emptied.to_dict()["chamber"]["room"]["left_wall"] is False
