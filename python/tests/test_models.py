"""saltus.models: the command line's `saltus models --json`, as Python objects."""

import json

import pytest

import saltus


def test_models_is_the_json_listing(cli):
    code, out, err = cli("models", "--json")
    assert code == 0, err
    assert saltus.models() == json.loads(out)
    code, out, err = cli("models", "drag", "--json")
    assert saltus.models("drag") == json.loads(out)
    assert {m["family"] for m in saltus.models()} == {
        "drag",
        "hindrance",
        "viscosity",
        "granular",
        "turbulence",
        "fluctuation",
        "wall_friction",
    }


def test_an_unknown_family_lists_the_known_ones(cli):
    code, _, err = cli("models", "dragg")
    assert code == 2
    with pytest.raises(ValueError) as e:
        saltus.models("dragg")
    assert f"error: {e.value}" == err.strip()


def test_every_default_is_inside_its_range():
    # the listing's ranges are the ones the loader checks: a default outside would be refused
    for m in saltus.models():
        for p in m["parameters"]:
            lo, hi = p["range"][1:-1].split(", ")
            lo_v, hi_v = float(lo), float(hi)
            v = p["default"]
            assert (v > lo_v if p["range"][0] == "(" else v >= lo_v), (m["name"], p)
            assert (v < hi_v if p["range"][-1] == ")" else v <= hi_v), (m["name"], p)
