"""Every bad parameter gives one FieldError naming the element and the parameter."""

from __future__ import annotations

import pytest

from assistbot.fields import FieldError, Network


def spec(**field_overrides):
    f = {"items": ["a", "b"], "tau": 0.1, "h": -3.0}
    f.update(field_overrides)
    return {"dt": 0.005, "fields": {"F": f, "G": {"items": ["x", "y", "z"], "tau": 0.1, "h": -3.0}}}


@pytest.mark.parametrize("overrides, key, words", [
    ({"tua": 0.1}, "tua", "unknown parameter"),
    ({"tau": -0.1}, "tau", "must be > 0"),
    ({"tau": 0.005}, "tau", "too large for a stable Euler step"),
    ({"h": 1.0}, "h", "must be negative"),
    ({"beta": 0}, "beta", "must be > 0"),
    ({"kernel": {"A": 1.0, "sigma": 0.0}}, "kernel.sigma", "must be > 0"),
    ({"kernel": {"A": 1.0, "width": 2.0}}, "kernel.width", "unknown parameter"),
    ({"items": ["a", "a"]}, "items", "unique"),
    ({"noise": -1}, "noise", ">= 0"),
    ({"tau": "fast"}, "tau", "must be a number"),
])
def test_bad_field_parameter(overrides, key, words):
    with pytest.raises(FieldError) as err:
        Network.from_dict(spec(**overrides))
    assert err.value.where == "field 'F'"
    assert err.value.key == key
    assert words in err.value.message
    assert str(err.value).startswith(f"error: field 'F': {key}: ")


def test_unknown_item_in_coupling_table_names_the_coupling_and_item():
    d = spec()
    d["couplings"] = [{"source": "F", "target": "G", "table": {"x": {"c": 1.0}}}]
    with pytest.raises(FieldError) as err:
        Network.from_dict(d)
    assert err.value.where == "coupling 'F->G'"
    assert err.value.key == "table.x.c"
    assert "known: a, b" in err.value.message


def test_mismatched_table_shape():
    d = spec()
    d["couplings"] = [{"source": "F", "target": "G", "table": [[1, 0], [0, 1]]}]
    with pytest.raises(FieldError) as err:
        Network.from_dict(d)
    assert err.value.key == "table"
    assert "(2, 2)" in err.value.message and "(3, 2)" in err.value.message


def test_matrix_table_of_the_right_shape_is_accepted():
    d = spec()
    d["couplings"] = [{"source": "F", "target": "G", "k": 2.0, "table": [[1, 0], [0, 1], [0.5, 0]]}]
    net = Network.from_dict(d)
    assert net.get("couplings.F->G.table.z.a") == 0.5


def test_unknown_field_in_coupling():
    d = spec()
    d["couplings"] = [{"source": "F", "target": "H", "table": {}}]
    with pytest.raises(FieldError) as err:
        Network.from_dict(d)
    assert err.value.key == "target" and "known: F, G" in err.value.message


def test_unknown_item_and_field_at_run_time():
    net = Network.from_dict(spec())
    with pytest.raises(FieldError) as err:
        net.set_stimulus("F", "q", 1.0)
    assert err.value.where == "field 'F'" and err.value.key == "q"
    with pytest.raises(FieldError) as err:
        net.u("Nope")
    assert err.value.key == "Nope"


def test_unknown_parameter_path_and_rejected_value_leave_the_network_unchanged():
    net = Network.from_dict(spec())
    with pytest.raises(FieldError) as err:
        net.set("fields.F.kernel.B", 1.0)
    assert err.value.key == "fields.F.kernel.B"
    with pytest.raises(FieldError):
        net.set("fields.F.tau", -1.0)
    assert net.get("fields.F.tau") == 0.1


def test_unknown_backend_and_top_level_key():
    with pytest.raises(FieldError) as err:
        Network.from_dict(spec(), backend="gpu")
    assert err.value.key == "backend"
    d = spec()
    d["fieldz"] = {}
    with pytest.raises(FieldError) as err:
        Network.from_dict(d)
    assert err.value.where == "network" and err.value.key == "fieldz"


def test_yaml_error_names_the_file(tmp_path):
    p = tmp_path / "net.yaml"
    p.write_text("dt: 0.005\nfields:\n  F: {items: [a], tau: -1, h: -3}\n")
    with pytest.raises(FieldError) as err:
        Network.from_yaml(p)
    assert str(p) in err.value.where and err.value.key == "tau"


def test_a_plane_with_bad_parameters_names_them():
    with pytest.raises(FieldError) as err:
        Network.from_dict({"dt": 0.005, "fields": {"T": {"shape": [10, 10], "tau": 0.0}}})
    assert err.value.key == "tau"
    with pytest.raises(FieldError) as err:
        Network.from_dict({"dt": 0.05, "fields": {"T": {"shape": [10, 10], "tau": 0.05}}})
    assert "dt=0.05" in err.value.message
