"""CJK faces beside the reading-direction detector's font splits (jdraw.data.fonts).

Two groups, each font in neither of the other's nor in any split of
:data:`jdraw.data.fonts.DETECTOR_TRAIN`, ``DETECTOR_VAL`` or ``DETECTOR_EVAL``:

* :data:`DETECTOR_CHECK`: faces of the scripts whose detector mistakes cost most (a
  han character read right to left is planned backwards), never fitted on, never
  setting a threshold, never held out; ``bench/detector_rates.py --more-faces``
  reads them to check a detector.
* :data:`DETECTOR_MORE_TRAIN`: more faces to fit on, only where a config asks
  (``more_cjk``, ``configs/reading_direction.py:elastic_cjk``).
"""

from __future__ import annotations

# name: (file under /usr/share/fonts, the Debian package that ships it)
CJK_FACES = {
    "arphic_bsmi": ("bsmi00lp.ttf", "fonts-arphic-bsmi00lp"),
    "arphic_gbsn": ("gbsn00lp.ttf", "fonts-arphic-gbsn00lp"),
    "arphic_gkai": ("gkai00mp.ttf", "fonts-arphic-gkai00mp"),
    "hanazono": ("HanaMinA.ttf", "fonts-hanazono"),
    "ipaex_mincho": ("ipaexm.ttf", "fonts-ipaexfont-mincho"),
    "baekmuk_batang": ("batang.ttf", "fonts-baekmuk"),
    "baekmuk_gulim": ("gulim.ttf", "fonts-baekmuk"),
    "wqy_microhei": ("wqy-microhei.ttc", "fonts-wqy-microhei"),
    "cwtex_ming": ("cwming.ttf", "fonts-cwtex-ming"),
    "arphic_bkai": ("bkai00mp.ttf", "fonts-arphic-bkai00mp"),
    "takao_mincho": ("TakaoMincho.ttf", "fonts-takao-mincho"),
    "vl_gothic": ("VL-Gothic-Regular.ttf", "fonts-vlgothic"),
    "un_pen": ("UnPen.ttf", "fonts-unfonts-extra"),
    "un_pilgia": ("UnPilgia.ttf", "fonts-unfonts-extra"),
}
DETECTOR_CHECK = {
    "han": ["arphic_bsmi", "arphic_gbsn", "arphic_gkai", "hanazono", "ipaex_mincho"],
    "kana": ["hanazono", "ipaex_mincho"],
    "hangul": ["baekmuk_batang", "baekmuk_gulim"],
}
DETECTOR_MORE_TRAIN = {
    "han": ["wqy_microhei", "cwtex_ming", "arphic_bkai", "takao_mincho"],
    "kana": ["takao_mincho", "vl_gothic"],
    "hangul": ["un_pen", "un_pilgia"],
}
