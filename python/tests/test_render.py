"""``fairsub.render``'s typed keywords against ``fairsub render``'s options: the same pixels for
the same options, the command's defaults, and a ValueError naming the keyword for a bad value."""

import re

import numpy as np
import pytest

import fairsub
from test_against_cli import _png_pixels

NET = "gallery:cnet-5-saddle"


@pytest.fixture(scope="module")
def surf():
    return fairsub.surface(NET, "catmull-clark", rings=3)


# (command-line words, keywords) pairs that must draw the same picture
CASES = [
    (["--size", "72x48"], dict(size=(72, 48))),
    (
        ["--size", "72x48", "--mode", "highlight", "--azimuth", "-30", "--elevation", "55",
         "--stripes", "7", "--stripe-width", "0.3", "--light-angle", "20",
         "--overlay", "net,patches", "--aa", "1"],
        dict(mode="highlight", size=(72, 48), azimuth=-30, elevation=55.0, stripes=7,
             stripe_width=0.3, light_angle=20.0, overlay=["net", "patches"], aa=1),
    ),
    (
        ["--size", "64x64", "--mode", "mean", "--focus", "vertex:0", "--zoom-rings", "2..3",
         "--range", "0.5", "--fov", "25", "--no-legend"],
        dict(mode="mean", size=64, focus=0, zoom_rings=(2, 3), range=0.5, fov=25,
             legend=False),
    ),
]


@pytest.mark.parametrize("words,look", CASES)
def test_keywords_draw_what_the_command_draws(cli, tmp_path, surf, words, look):
    png = tmp_path / "cli.png"
    code, _, err = cli("render", NET, "--scheme", "catmull-clark", "--rings", 3, *words,
                       "-o", png)
    assert code == 0, err
    img = fairsub.render(surf, **look)
    want = _png_pixels(png)
    assert img.dtype == np.uint8 and img.shape == want.shape
    assert np.array_equal(img, want)


def test_the_spellings_of_a_value_agree(surf):
    base = fairsub.render(surf, "mean", (64, 48), focus=0, zoom_rings=(2, 3),
                          overlay=["net", "patches"], legend=False)
    same = fairsub.render(surf, mode="mean", size="64x48", focus="vertex:0",
                          zoom_rings="2..3", overlay="net,patches", no_legend=True)
    assert np.array_equal(base, same)
    # and the keywords reach the picture: another azimuth draws another one
    other = fairsub.render(surf, "mean", (64, 48), focus=0, zoom_rings=(2, 3),
                           overlay=["net", "patches"], legend=False, azimuth=30)
    assert not np.array_equal(base, other)


def test_the_defaults_are_the_commands(cli, surf):
    d = fairsub.render_defaults()
    assert d["mode"] == "shaded" and d["size"] == (800, 800) and d["legend"] is True
    _, out, _ = cli("render", "--help")
    for key, flag in [("aa", "--aa"), ("azimuth", "--azimuth"), ("elevation", "--elevation"),
                      ("fov", "--fov"), ("stripes", "--stripes"),
                      ("stripe_width", "--stripe-width"), ("light_angle", "--light-angle")]:
        m = re.search(re.escape(flag) + r" <[A-Z_]+>\n.*?\[default: ([^\]]+)\]", out, re.S)
        assert m, flag
        assert float(m.group(1)) == d[key], (flag, m.group(1), d[key])
    # every default given explicitly draws the default picture
    explicit = dict(d, size=(48, 40), overlay=d["overlay"] or None)
    assert np.array_equal(fairsub.render(surf, **explicit), fairsub.render(surf, size=(48, 40)))


def test_bad_values_raise_value_error_naming_the_keyword(cli, tmp_path, surf):
    cases = [
        (dict(stripe_width=1.5), "bad stripe_width=1.5: must lie strictly between 0 and 1",
         ["--stripe-width", "1.5"]),
        (dict(size=(4, 64)),
         "bad size=4x64: width and height must be between 8 and 16384 pixels",
         ["--size", "4x64"]),
        (dict(aa=9), "bad aa=9: samples per pixel axis must be 1 to 8", ["--aa", "9"]),
        (dict(fov=200), "bad fov=200: the field of view must be between 1 and 170 degrees",
         ["--fov", "200"]),
    ]
    for look, message, words in cases:
        with pytest.raises(ValueError) as e:
            fairsub.render(surf, **look)
        assert str(e.value) == message
        # the command line gives the same reason under its flag's name
        code, _, err = cli("render", NET, *words, "-o", tmp_path / "x.png")
        assert code == 1
        _, value, reason = re.fullmatch(r"bad (\w+)=(\S+): (.*)", message).groups()
        assert err.strip() == f"error: invalid argument: bad {words[0]} {value}: {reason}"
    for look, start in [
        (dict(mode="wavy"), "mode: unknown mode 'wavy'"),
        (dict(focus="edge:3"), "focus: bad element 'edge:3'"),
        (dict(zoom_rings="3..1"), "zoom_rings: bad ring range '3..1'"),
        (dict(zoom_rings=(0, 2)), "bad zoom_rings=0..2: rings are numbered from 1"),
        (dict(overlay="grid"), "overlay: unknown overlay 'grid'"),
        (dict(azimuth="north"), "bad azimuth='north': expected a number"),
        (dict(aa=1.5), "bad aa=1.5: expected a whole number"),
        (dict(legend="no"), "bad legend='no': expected True or False"),
        (dict(size=(64, -1)), "bad size=-1: expected a whole number"),
        (dict(colour="red"), "unknown render option 'colour' (the options are mode, size"),
    ]:
        with pytest.raises(ValueError) as e:
            fairsub.render(surf, **look)
        assert str(e.value).startswith(start), (look, str(e.value))


def test_a_net_renders_and_refuses_curvature(tmp_path, cli):
    net = fairsub.read("gallery:cube")
    img = fairsub.render(net, "highlight", size=(40, 32))
    assert img.shape == (32, 40, 3) and len(np.unique(img.reshape(-1, 3), axis=0)) > 2
    with pytest.raises(ValueError, match="needs exact patches"):
        fairsub.render(net, "mean", size=(40, 32))
