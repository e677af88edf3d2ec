"""Fixtures shared by the cloudscape tests."""
from __future__ import annotations

import pytest

from pywarp.clouds.settings import CloudscapeSettings


@pytest.fixture(scope="module")
def small_textures():
    """The cloudscape's textures at small sizes (32^3 base, 16^3 detail, 32^2 curl, 128^2 weather): seconds to make."""
    from pywarp.clouds.cloudscape import RenderTextures
    return RenderTextures.generate(CloudscapeSettings(base_size=32, detail_size=16, curl_size=32, weather_size=128))
