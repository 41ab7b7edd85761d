"""The live preview reads an answer exactly as the checker will, and never compares it with anything."""

from grader.web.student.preview import allowed_names, expected_dimension, preview

TENSION = {"name": "tension", "kind": "expression", "reference": "g*m/3", "dimension": "kg*m*s^-2",
           "variables": {"g": {"dimension": "m*s^-2", "domain": "positive"},
                         "m": {"dimension": "kg", "domain": "positive"}}}


def test_implicit_products_are_read_and_explained():
    result = preview(TENSION, "mg/3")
    assert result["ok"] and result["latex"] == r"\frac{g m}{3}"
    assert "read 'mg' as m·g" in result["notes"]
    assert result["dimension"] == "a force (kg·m/s²)" and result["warning"] is None


def test_a_typo_is_an_error_with_its_position_and_a_hint():
    result = preview(TENSION, "m*g*sin(thta)")
    assert not result["ok"]
    assert result["error"]["position"] == 8 and result["error"]["code"] == "unknown_name"


def test_a_wrong_dimension_is_a_warning_not_an_error():
    result = preview(TENSION, "m")
    assert result["ok"] and "should be a force" in result["warning"]


def test_empty_and_overlong_texts_say_so():
    assert preview(TENSION, "  ")["error"]["code"] == "empty"
    assert preview(TENSION, "m+" * 3000)["error"]["code"] == "too_long"


def test_the_preview_never_carries_the_reference():
    assert "g*m/3" not in str(preview(TENSION, "m*g"))


def test_the_names_and_dimension_a_student_may_know():
    assert [n["name"] for n in allowed_names(TENSION)] == ["g", "m"]
    assert expected_dimension(TENSION) == "a force (kg·m/s²)"
