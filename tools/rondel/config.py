"""The resolved configuration of a run (INI text: config.ini, the `config` attribute of an HDF5 file)."""
import configparser

from .errors import RondelFileError

TRUE = ("1", "true", "yes", "on")
FALSE = ("0", "false", "no", "off", "")


class Config:
    """Sections and keys of a Rondel configuration, values as text.

    `cfg["domain"]["xlo"]` gives the text; `cfg.get("domain", "xlo")`, `cfg.getfloat(...)`,
    `cfg.getbool(...)` take a default; `cfg.sections()` lists the sections; `cfg.text` is the source."""

    def __init__(self, text, source="<config>"):
        self.text = text or ""
        self.source = str(source)
        cp = configparser.ConfigParser(interpolation=None, strict=False, inline_comment_prefixes=None)
        cp.optionxform = str
        try:
            cp.read_string(self.text, source=self.source)
        except configparser.Error as e:
            raise RondelFileError(self.source, f"not readable INI text ({str(e).splitlines()[0]})") from None
        self._data = {s: {k: v.strip() for k, v in cp.items(s)} for s in cp.sections()}

    @classmethod
    def from_file(cls, path):
        """The configuration in an INI file (a run's config.ini)."""
        try:
            with open(path) as f:
                return cls(f.read(), path)
        except OSError as e:
            raise RondelFileError(path, f"cannot be read ({e.strerror})") from None

    def sections(self):
        return list(self._data)

    def __contains__(self, section):
        return section in self._data

    def __getitem__(self, section):
        return self._data[section]

    def as_dict(self):
        """{section: {key: text}} (a copy)."""
        return {s: dict(kv) for s, kv in self._data.items()}

    def get(self, section, key, default=None):
        return self._data.get(section, {}).get(key, default)

    def getfloat(self, section, key, default=None):
        v = self.get(section, key)
        if v is None or v == "":
            return default
        try:
            return float(v)
        except ValueError:
            raise RondelFileError(self.source, f"[{section}] {key} = '{v}' is not a number") from None

    def getbool(self, section, key, default=False):
        v = self.get(section, key)
        if v is None:
            return default
        if v.lower() in TRUE:
            return True
        if v.lower() in FALSE:
            return False
        raise RondelFileError(self.source, f"[{section}] {key} = '{v}' is not a boolean")

    def domain(self):
        """[domain] as dict xlo, xhi, ylo, yhi (float or None), periodic_x, periodic_y (bool)."""
        dom = {k: self.getfloat("domain", k) for k in ("xlo", "xhi", "ylo", "yhi")}
        for axis in ("x", "y"):
            dom[f"periodic_{axis}"] = self.getbool("domain", f"periodic_{axis}")
            if dom[f"periodic_{axis}"] and (dom[f"{axis}lo"] is None or dom[f"{axis}hi"] is None):
                raise RondelFileError(self.source, f"periodic in {axis} but [domain] {axis}lo/{axis}hi are missing")
        return dom

    def scene_name(self):
        """A short name of the run for titles: the last part of run.output (e.g. 'pile'), else ''."""
        out = (self.get("run", "output") or "").rstrip("/")
        return out.rsplit("/", 1)[-1]

    def laws(self):
        """'normal/tangential/rolling' laws of [contact] (Rondel's defaults where a key is absent)."""
        return "/".join(self.get("contact", k, d) for k, d in
                        (("normal", "linear"), ("tangential", "coulomb"), ("rolling", "none")))

    def __repr__(self):
        return f"Config({self.source!r}, sections={self.sections()})"
