"""Words set in system fonts: the reading-direction detector's data, benches and examples.

Fonts come from Debian packages (``apt-get install <package>``); none is
needed at run time. :data:`FONTS` names each font file and its package, so a
missing one is reported with the command that installs it. Which fonts train
the reading-direction detector and which measure it is fixed here
(:data:`DETECTOR_TRAIN`, :data:`DETECTOR_EVAL`), so the two never overlap.
"""

from __future__ import annotations

import dataclasses
import functools
import pathlib

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from jdraw.data.cjk_faces import CJK_FACES

FONT_DIRS = (pathlib.Path("/usr/share/fonts"),)


@dataclasses.dataclass(frozen=True)
class Font:
    """One font face: a file under ``/usr/share/fonts`` and the Debian package shipping it."""

    file: str  # file name, found anywhere under FONT_DIRS
    package: str
    index: int = 0  # face in a .ttc collection


class FontMissing(FileNotFoundError):
    """A font file is not installed; the message names its Debian package."""


# Faces of fonts-ukij-uyghur (UKIJ<face>.ttf).
_UKIJ = (
    "Tuz", "Basma", "Ekran", "Qolyazma", "Ku", "Sls", "Nsq", "Junu", "Di", "Me", "Tor", "Ru",
    "Zilwa", "Saet", "Es", "Kesme", "Chechek",
)  # fmt: skip
# Hebrew faces of fonts-ldco (<face>.ttf), Louis Davis & Co.
_LDCO = (
    "Amit", "Daniel", "ECO", "HarSinai", "Hidekel", "Josef", "Kimchi", "Lilach", "Miso", "Mixer",
    "Neo", "Noam", "PatchSans", "PatchSerif", "PatchStencil", "Sayphan", "Skechers", "Sticks",
    "Strokes", "YamSuf",
)  # fmt: skip

# name -> font. Culmus, KACST, Arabeyes, FarsiWeb, UKIJ, SIL, URW and a few more train the
# detector (a few of them only set its threshold); Noto, FreeFont, Amiri, SIL Ezra and
# Dancing Script measure it and write the examples.
FONTS = {
    # Hebrew
    "david": Font("DavidCLM-Medium.otf", "culmus"),
    "frank_ruehl": Font("FrankRuehlCLM-Medium.ttf", "culmus"),
    "hadasim": Font("HadasimCLM-Regular.ttf", "culmus"),
    "keter": Font("KeterYG-Medium.ttf", "culmus"),
    "miriam": Font("MiriamCLM-Book.ttf", "culmus"),
    "nachlieli": Font("NachlieliCLM-Light.otf", "culmus"),
    "simple": Font("SimpleCLM-Medium.ttf", "culmus"),
    "shofar": Font("ShofarRegular.ttf", "culmus"),
    "stam": Font("StamAshkenazCLM.ttf", "culmus"),
    "miriam_mono": Font("MiriamMonoCLM-Book.ttf", "culmus"),
    "stam_sefarad": Font("StamSefaradCLM.ttf", "culmus"),
    "anka": Font("AnkaCLM-Bold.otf", "culmus-fancy"),
    "gladia": Font("GladiaCLM-Bold.otf", "culmus-fancy"),
    "hillel": Font("HillelCLM-Medium.otf", "culmus-fancy"),
    "horev": Font("HorevCLM-Heavy.otf", "culmus-fancy"),
    "journal": Font("JournalCLM-Light.otf", "culmus-fancy"),
    "ozrad": Font("OzradCLM-Bold.otf", "culmus-fancy"),
    "trashim": Font("TrashimCLM-Bold.otf", "culmus-fancy"),
    "dorian": Font("DorianCLM-Book.ttf", "culmus-fancy"),
    "makabi": Font("MakabiYG.ttf", "culmus-fancy"),
    "shmulik": Font("ShmulikCLM.ttf", "culmus-fancy"),
    "taamey_ashkenaz": Font("TaameyAshkenaz-Medium.ttf", "culmus-fancy"),
    "taamey_david": Font("TaameyDavidCLM-Medium.ttf", "culmus-fancy"),
    "taamey_frank": Font("TaameyFrankCLM-Medium.ttf", "culmus-fancy"),
    "keter_aram_tsova": Font("KeterAramTsova.ttf", "culmus-fancy"),
    "noto_rashi_hebrew": Font("NotoRashiHebrew-Regular.ttf", "fonts-noto-core"),
    "noto_sans_hebrew": Font("NotoSansHebrew-Regular.ttf", "fonts-noto-core"),
    "noto_serif_hebrew": Font("NotoSerifHebrew-Regular.ttf", "fonts-noto-core"),
    "ezra": Font("SILEOT.ttf", "fonts-sil-ezra"),
    **{f"ldco_{k.lower()}": Font(f"{k}.ttf", "fonts-ldco") for k in _LDCO},
    # Arabic script
    "kacst_book": Font("KacstBook.ttf", "fonts-kacst"),
    "kacst_naskh": Font("KacstNaskh.ttf", "fonts-kacst"),
    "kacst_office": Font("KacstOffice.ttf", "fonts-kacst"),
    "kacst_farsi": Font("KacstFarsi.ttf", "fonts-kacst"),
    "kacst_letter": Font("KacstLetter.ttf", "fonts-kacst"),
    "kacst_pen": Font("KacstPen.ttf", "fonts-kacst"),
    "kacst_title": Font("KacstTitle.ttf", "fonts-kacst"),
    "ae_arab": Font("ae_Arab.ttf", "fonts-arabeyes"),
    "ae_cortoba": Font("ae_Cortoba.ttf", "fonts-arabeyes"),
    "ae_furat": Font("ae_Furat.ttf", "fonts-arabeyes"),
    "ae_granada": Font("ae_Granada.ttf", "fonts-arabeyes"),
    "ae_hani": Font("ae_Hani.ttf", "fonts-arabeyes"),
    "ae_khalid": Font("ae_Khalid.ttf", "fonts-arabeyes"),
    "ae_nada": Font("ae_Nada.ttf", "fonts-arabeyes"),
    "ae_salem": Font("ae_Salem.ttf", "fonts-arabeyes"),
    "ae_tholoth": Font("ae_Tholoth.ttf", "fonts-arabeyes"),
    "kacst_one": Font("KacstOne.ttf", "fonts-kacst-one"),
    "kacst_qurn": Font("KacstQurn.ttf", "fonts-kacst"),
    "kacst_screen": Font("KacstScreen.ttf", "fonts-kacst"),
    "kacst_title_l": Font("KacstTitleL.ttf", "fonts-kacst"),
    "homa": Font("homa.ttf", "fonts-farsiweb"),
    "nazli": Font("nazli.ttf", "fonts-farsiweb"),
    "titr": Font("titr.ttf", "fonts-farsiweb"),
    "thabit": Font("Thabit.ttf", "fonts-hosny-thabit"),
    "lateef": Font("Lateef-Regular.ttf", "fonts-sil-lateef"),
    "harmattan": Font("Harmattan-Regular.ttf", "fonts-sil-harmattan"),
    **{f"ukij_{k.lower()}": Font(f"UKIJ{k}.ttf", "fonts-ukij-uyghur") for k in _UKIJ},
    "scheherazade": Font("Scheherazade-Regular.ttf", "fonts-sil-scheherazade"),
    "noto_naskh_arabic": Font("NotoNaskhArabic-Regular.ttf", "fonts-noto-core"),
    "noto_sans_arabic": Font("NotoSansArabic-Regular.ttf", "fonts-noto-core"),
    "noto_kufi_arabic": Font("NotoKufiArabic-Regular.ttf", "fonts-noto-core"),
    "noto_nastaliq_urdu": Font("NotoNastaliqUrdu-Regular.ttf", "fonts-noto-core"),
    "amiri": Font("Amiri-Regular.ttf", "fonts-hosny-amiri"),
    "free_farsi": Font("FreeFarsi.ttf", "fonts-freefarsi"),
    "free_farsi_bold": Font("FreeFarsi-Bold.ttf", "fonts-freefarsi"),
    "lemonada": Font("Lemonada-Regular.otf", "fonts-lemonada"),
    "alkalami": Font("Alkalami-Regular.ttf", "fonts-sil-alkalami"),
    "nafees": Font("NafeesWeb.ttf", "fonts-nafees"),
    "paktype_naskh_basic": Font("PakType Naskh Basic.ttf", "fonts-paktype"),
    "paktype_naqsh": Font("PakType Naqsh.ttf", "fonts-paktype"),
    "paktype_ajrak": Font("PakType Ajrak.ttf", "fonts-paktype"),
    "paktype_tehreer": Font("PakType Tehreer.ttf", "fonts-paktype"),
    # Latin, Greek, Cyrillic and more
    "dejavu_sans": Font("DejaVuSans.ttf", "fonts-dejavu-core"),
    "dejavu_serif": Font("DejaVuSerif.ttf", "fonts-dejavu-core"),
    "liberation_sans": Font("LiberationSans-Regular.ttf", "fonts-liberation"),
    "liberation_serif": Font("LiberationSerif-Regular.ttf", "fonts-liberation"),
    "kaushan": Font("KaushanScript-Regular.otf", "fonts-kaushanscript"),
    "nimbus_sans": Font("NimbusSans-Regular.otf", "fonts-urw-base35"),
    "nimbus_roman": Font("NimbusRoman-Regular.otf", "fonts-urw-base35"),
    "c059": Font("C059-Roman.otf", "fonts-urw-base35"),
    "p052": Font("P052-Roman.otf", "fonts-urw-base35"),
    "urw_gothic": Font("URWGothic-Book.otf", "fonts-urw-base35"),
    "urw_bookman": Font("URWBookman-Light.otf", "fonts-urw-base35"),
    "z003": Font("Z003-MediumItalic.otf", "fonts-urw-base35"),
    "andika": Font("Andika-Regular.ttf", "fonts-sil-andika"),
    "charis": Font("CharisSIL-Regular.ttf", "fonts-sil-charis"),
    "gentium": Font("Gentium-R.ttf", "fonts-sil-gentium"),
    "comfortaa": Font("Comfortaa-Regular.ttf", "fonts-comfortaa"),
    "breip": Font("Breip.ttf", "fonts-breip"),
    "dkg": Font("dkg.ttf", "fonts-dkg-handwriting"),
    "humor_sans": Font("Humor-Sans.ttf", "fonts-humor-sans"),
    "comic_neue": Font("ComicNeue-Regular.otf", "fonts-comic-neue"),
    "lobster_two": Font("LobsterTwo-Regular.otf", "fonts-lobstertwo"),
    "arphic_ukai": Font("ukai.ttc", "fonts-arphic-ukai"),
    "arphic_uming": Font("uming.ttc", "fonts-arphic-uming"),
    "wqy_zenhei": Font("wqy-zenhei.ttc", "fonts-wqy-zenhei"),
    "ipa_gothic": Font("ipag.ttf", "fonts-ipafont-gothic"),
    "ipa_mincho": Font("ipam.ttf", "fonts-ipafont-mincho"),
    "un_batang": Font("UnBatang.ttf", "fonts-unfonts-core"),
    **{name: Font(*where) for name, where in CJK_FACES.items()},
    "un_dotum": Font("UnDotum.ttf", "fonts-unfonts-core"),
    "nanum_gothic": Font("NanumGothic.ttf", "fonts-nanum"),
    "nanum_myeongjo": Font("NanumMyeongjo.ttf", "fonts-nanum"),
    "noto_sans": Font("NotoSans-Regular.ttf", "fonts-noto-core"),
    "noto_serif": Font("NotoSerif-Regular.ttf", "fonts-noto-core"),
    "free_sans": Font("FreeSans.ttf", "fonts-freefont-ttf"),
    "free_serif": Font("FreeSerif.ttf", "fonts-freefont-ttf"),
    "dancing_script": Font("DancingScript-Regular.otf", "fonts-dancingscript"),
    "noto_sans_devanagari": Font("NotoSansDevanagari-Regular.ttf", "fonts-noto-core"),
    "noto_serif_devanagari": Font("NotoSerifDevanagari-Regular.ttf", "fonts-noto-core"),
    "noto_sans_tamil": Font("NotoSansTamil-Regular.ttf", "fonts-noto-core"),
    "noto_serif_tamil": Font("NotoSerifTamil-Regular.ttf", "fonts-noto-core"),
    "noto_sans_bengali": Font("NotoSansBengali-Regular.ttf", "fonts-noto-core"),
    "noto_sans_thai": Font("NotoSansThai-Regular.ttf", "fonts-noto-core"),
    "noto_sans_ethiopic": Font("NotoSansEthiopic-Regular.ttf", "fonts-noto-core"),
    "noto_sans_armenian": Font("NotoSansArmenian-Regular.ttf", "fonts-noto-core"),
    "noto_sans_georgian": Font("NotoSansGeorgian-Regular.ttf", "fonts-noto-core"),
    # Noto Sans CJK collection faces: 0 JP, 1 KR, 2 SC
    "noto_sans_cjk_jp": Font("NotoSansCJK-Regular.ttc", "fonts-noto-cjk", 0),
    "noto_sans_cjk_kr": Font("NotoSansCJK-Regular.ttc", "fonts-noto-cjk", 1),
    "noto_sans_cjk_sc": Font("NotoSansCJK-Regular.ttc", "fonts-noto-cjk", 2),
    "noto_serif_cjk_jp": Font("NotoSerifCJK-Regular.ttc", "fonts-noto-cjk", 0),
    "noto_serif_cjk_kr": Font("NotoSerifCJK-Regular.ttc", "fonts-noto-cjk", 1),
    "noto_serif_cjk_sc": Font("NotoSerifCJK-Regular.ttc", "fonts-noto-cjk", 2),
}

RTL_SCRIPTS = ("hebrew", "arabic")


def _chars(*ranges: tuple[int, int]) -> str:
    return "".join(chr(c) for a, b in ranges for c in range(a, b + 1))


# Letters random words are drawn from, per script.
ALPHABETS = {
    "hebrew": _chars((0x05D0, 0x05EA)),
    "arabic": _chars((0x0628, 0x063A), (0x0641, 0x064A)) + "اپچژگکیہےٹڈڑںۓ",
    "latin": _chars((0x61, 0x7A)) * 3 + _chars((0x41, 0x5A)) + "éèàçüöäñ",
    "greek": _chars((0x03B1, 0x03C9)) * 2 + _chars((0x0391, 0x03A9)).replace("\u03a2", ""),
    "cyrillic": _chars((0x0430, 0x044F)) * 2 + _chars((0x0410, 0x042F)),
    "armenian": _chars((0x0561, 0x0586)),
    "georgian": _chars((0x10D0, 0x10F0)),
    "devanagari": _chars((0x0915, 0x0939)) * 2 + _chars((0x093E, 0x094C)),
    "bengali": _chars((0x0995, 0x09A8), (0x09AA, 0x09B0)) * 2 + _chars((0x09BE, 0x09C4)),
    "tamil": "கஙசஞடணதநபமயரலவழளறன" * 2 + "ாிீுூெேை",
    "thai": _chars((0x0E01, 0x0E2E)),
    "ethiopic": _chars((0x1200, 0x1248)),
    "hangul": _chars((0xAC00, 0xD7A3)),
    "kana": _chars((0x3042, 0x3093), (0x30A2, 0x30F3)),
    "han": _chars((0x4E00, 0x6FFF)),
}

# Which fonts train the reading-direction detector, which set its threshold (DETECTOR_VAL)
# and which measure it (DETECTOR_EVAL): the three never overlap.
DETECTOR_TRAIN = {
    "hebrew": [
        "david", "frank_ruehl", "hadasim", "keter", "miriam", "nachlieli", "simple",
        "shofar", "stam", "stam_sefarad", "anka", "gladia", "horev", "journal", "ozrad",
        "trashim", "makabi", "taamey_ashkenaz", "taamey_david", "taamey_frank",
        "keter_aram_tsova", "noto_rashi_hebrew", "dejavu_sans",
        *(f"ldco_{k.lower()}" for k in _LDCO if k not in ("Mixer", "Noam")),
    ],
    "arabic": [
        "kacst_book", "kacst_naskh", "kacst_office", "kacst_farsi", "kacst_letter",
        "kacst_pen", "kacst_title", "kacst_one", "kacst_qurn", "kacst_title_l", "ae_arab",
        "ae_cortoba", "ae_furat", "ae_granada", "ae_hani", "ae_khalid", "ae_nada", "ae_salem",
        "ae_tholoth", "homa", "titr", "thabit", "lateef", "scheherazade", "ukij_tuz",
        "ukij_basma", "ukij_ekran", "ukij_qolyazma", "ukij_ku", "ukij_sls", "ukij_junu",
        "ukij_di", "ukij_me", "ukij_tor", "ukij_ru", "ukij_zilwa", "ukij_saet", "ukij_es",
        "ukij_kesme", "dejavu_sans", "free_farsi", "free_farsi_bold", "lemonada", "alkalami",
        "nafees", "paktype_naskh_basic", "paktype_naqsh", "paktype_ajrak",
    ],
    "latin": [
        "dejavu_sans", "dejavu_serif", "liberation_sans", "liberation_serif", "kaushan",
        "nimbus_sans", "nimbus_roman", "c059", "p052", "urw_bookman", "z003", "charis",
        "gentium", "comfortaa", "breip", "humor_sans", "comic_neue", "lobster_two",
    ],
    "greek": ["dejavu_sans", "dejavu_serif", "liberation_serif", "gentium", "c059"],
    "cyrillic": ["dejavu_sans", "dejavu_serif", "liberation_sans", "charis", "p052"],
    "armenian": ["dejavu_sans", "noto_sans_armenian"],
    "georgian": ["dejavu_sans", "noto_sans_georgian"],
    "devanagari": ["noto_sans_devanagari"],
    "bengali": ["noto_sans_bengali"],
    "tamil": ["noto_sans_tamil"],
    "thai": ["noto_sans_thai"],
    "ethiopic": ["noto_sans_ethiopic"],
    "hangul": ["noto_sans_cjk_kr", "un_dotum", "nanum_gothic", "nanum_myeongjo"],
    "kana": ["noto_sans_cjk_jp", "ipa_gothic", "wqy_zenhei"],
    "han": ["noto_sans_cjk_sc", "noto_sans_cjk_jp", "arphic_ukai", "wqy_zenhei", "ipa_gothic"],
}  # fmt: skip
DETECTOR_VAL = {
    "hebrew": ["hillel", "dorian", "shmulik", "miriam_mono", "ldco_mixer", "ldco_noam"],
    "arabic": [
        "harmattan", "nazli", "ukij_nsq", "ukij_chechek", "kacst_screen", "paktype_tehreer",
    ],
    "latin": ["urw_gothic", "andika", "dkg"],
    "cyrillic": ["andika"],
    "greek": ["urw_gothic"],
    "hangul": ["un_batang"],
    "kana": ["ipa_mincho"],
    "han": ["arphic_uming", "ipa_mincho"],
}  # fmt: skip
DETECTOR_EVAL = {
    "hebrew": ["noto_sans_hebrew", "noto_serif_hebrew", "free_sans", "free_serif", "ezra"],
    "arabic": ["noto_naskh_arabic", "noto_sans_arabic", "noto_kufi_arabic",
               "noto_nastaliq_urdu", "amiri", "free_serif"],
    "latin": ["noto_sans", "noto_serif", "free_sans", "free_serif", "dancing_script"],
    "greek": ["noto_sans", "noto_serif", "free_serif"],
    "cyrillic": ["noto_sans", "noto_serif", "free_serif"],
    "devanagari": ["noto_serif_devanagari"],
    "tamil": ["noto_serif_tamil"],
    "hangul": ["noto_serif_cjk_kr"],
    "kana": ["noto_serif_cjk_jp"],
    "han": ["noto_serif_cjk_sc"],
}  # fmt: skip

# Words of our own for the benches (never used to train the detector, which sees random letters).
WORDS = {
    "hebrew": (
        "שלום ספר בית ילד ילדה מים אור לחם שמש ירח כוכב עץ פרח כלב חתול סוס דג ציפור "
        "אבא אמא משפחה חבר עיר דרך שולחן כיסא חלון דלת מחשב עט מכתב תודה בוקר ערב "
        "לילה יום שנה זמן אהבה שמחה ים הר ארץ שמיים"
    ).split(),
    "arabic": (
        "سلام كتاب بيت ولد بنت ماء نور خبز شمس قمر نجمة شجرة وردة كلب قطة حصان سمكة "
        "طائر أب أم عائلة صديق مدينة طريق طاولة كرسي نافذة باب حاسوب قلم رسالة شكرا "
        "صباح مساء ليل يوم سنة وقت حب فرح بحر جبل أرض سماء"
    ).split(),
    "latin": (
        "hello world drawing robot letter planner write stroke order bonjour script "
        "pencil marker paper circle window garden yellow minute quick"
    ).split(),
}


@functools.cache
def font_path(name: str) -> pathlib.Path:
    """The installed file of font ``name`` (a key of :data:`FONTS`).

    Raises:
      FontMissing: not installed; the message says which Debian package ships it.
    """
    f = FONTS[name]
    for d in FONT_DIRS:
        hits = sorted(d.rglob(f.file))
        if hits:
            return hits[0]
    raise FontMissing(f"font {name!r} ({f.file}) is not installed: apt-get install {f.package}")


@functools.lru_cache(maxsize=256)
def _face(name: str, size: int) -> ImageFont.FreeTypeFont:
    return ImageFont.truetype(
        str(font_path(name)), size, index=FONTS[name].index, layout_engine=ImageFont.Layout.RAQM
    )


def _draw(text: str, name: str, size: int, stroke: int, direction: str | None) -> np.ndarray:
    face = _face(name, size)
    x0, y0, x1, y1 = face.getbbox(text, direction=direction, stroke_width=stroke)
    pad = 2 + stroke
    img = Image.new("L", (x1 - x0 + 2 * pad, y1 - y0 + 2 * pad), 0)
    ImageDraw.Draw(img).text(
        (pad - x0, pad - y0), text, font=face, fill=255, direction=direction, stroke_width=stroke,
        stroke_fill=255,
    )  # fmt: skip
    return np.asarray(img)


def covers(name: str, text: str) -> bool:
    """Whether font ``name`` has a glyph for every character of ``text`` (not its .notdef box)."""
    face = _face(name, 40)
    missing = face.getmask("\U0010fffd")
    box = (missing.size, bytes(missing))
    for ch in set(text) - {" "}:
        m = face.getmask(ch)
        if (m.size, bytes(m)) == box:
            return False
    return True


def render_word(
    text: str,
    font: str,
    height: int,
    *,
    pen: float = 0.0,
    margin: int = 8,
    direction: str | None = None,
) -> np.ndarray:
    """``uint8 [H, W]`` dark ink on white: ``text`` set in ``font``, its ink ``height`` px high.

    Args:
      text: shaped with libraqm, so Arabic letters join and Indic clusters form.
      font: a key of :data:`FONTS`.
      height: pixels from the ink's top to its bottom (within a pixel or two).
      pen: extra outline as a fraction of ``height`` (a thick marker); 0: the font's own weight.
      margin: white pixels around the ink.
      direction: ``"rtl"``, ``"ltr"`` or ``None`` (libraqm's guess from the text).
    """
    probe = _draw(text, font, 100, 0, direction)
    rows = np.flatnonzero(probe.max(1) > 127)
    ink_h = max(int(rows[-1] - rows[0] + 1), 1) if len(rows) else 100
    size = max(4, round(100 * height / ink_h))
    stroke = round(pen * height)
    img = _draw(text, font, size, stroke, direction)
    ys, xs = np.nonzero(img > 127)
    if len(ys):
        img = img[ys.min() : ys.max() + 1, xs.min() : xs.max() + 1]
    return 255 - np.pad(img, margin)


def first_letter_width(text: str, font: str, height: int, direction: str = "rtl") -> float:
    """Approximate advance of ``text``'s first (logical) letter at :func:`render_word`'s scale.

    The width ``text`` loses without its first letter; in right-to-left text
    that letter is the rightmost.
    """
    probe = _draw(text, font, 100, 0, direction)
    rows = np.flatnonzero(probe.max(1) > 127)
    size = max(4, round(100 * height / max(int(rows[-1] - rows[0] + 1), 1)))
    face = _face(font, size)
    return float(
        face.getlength(text, direction=direction) - face.getlength(text[1:], direction=direction)
    )


@functools.cache
def alphabet(script: str, font: str | None = None) -> str:
    """The letters of ``script`` (:data:`ALPHABETS`) that ``font`` has glyphs for (all if None)."""
    letters = ALPHABETS[script]
    if font is None:
        return letters
    return "".join(ch for ch in letters if covers(font, ch))


def random_word(
    script: str, rng: np.random.Generator, lo: int = 2, hi: int = 7, font: str | None = None
) -> str:
    """A random string of ``lo..hi`` letters of ``script`` that ``font`` can set."""
    letters = alphabet(script, font)
    n = int(rng.integers(lo, hi + 1))
    if script in ("hangul", "han", "kana"):
        n = max(1, n // 2)
    return "".join(letters[int(k)] for k in rng.integers(0, len(letters), n))
