#!/usr/bin/env python3
"""Derives the compact WordNet 3.0 data set that `src/words/wordnet.rs` compiles in.

Reads Princeton WordNet 3.0 as Debian's `wordnet-base` package ships it (index.noun,
data.noun, index.adj, index.verb, index.adv, the four *.exc files and cntlist.rev) and writes
`src/data/wordnet/`:

  nouns.tsv.zlib       noun lemmas, sorted, each with its senses in WordNet order
  synsets.tsv.zlib     noun synsets: lexicographer file, hypernyms, instance hypernyms
  words.tsv.zlib       adjective, verb and adverb lemmas with their parts of speech
  exceptions.tsv.zlib  the irregular forms of noun.exc, verb.exc, adj.exc, adv.exc
  LICENSE              the WordNet 3.0 licence, verbatim from the package's copyright file
  README.md            what the files hold and how to regenerate them

Each .zlib file is one zlib stream (level 9) of UTF-8 text; the formats are described in the
generated README. The output depends only on the WordNet files: same input, same bytes.

Source of the WordNet files, first that applies:
  --root DIR           an extracted package root (DIR/usr/share/wordnet, DIR/usr/share/doc/...)
  /usr/share/wordnet   when wordnet-base is installed
  otherwise            `apt-get download wordnet-base` into a temporary directory and
                       `dpkg-deb -x` it there (no installation, nothing left behind)

Usage: python3 scripts/wordnet_data.py [--root DIR] [--out DIR]
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(ROOT, "src", "data", "wordnet")
PACKAGE = "wordnet-base"

# The lexicographer files by number, as listed in WordNet's lexnames(5WN). The Debian package
# does not ship the `lexnames` file itself, so the fixed table is written here once.
LEXNAMES = [
    "adj.all", "adj.pert", "adv.all", "noun.Tops", "noun.act", "noun.animal",
    "noun.artifact", "noun.attribute", "noun.body", "noun.cognition", "noun.communication",
    "noun.event", "noun.feeling", "noun.food", "noun.group", "noun.location", "noun.motive",
    "noun.object", "noun.person", "noun.phenomenon", "noun.plant", "noun.possession",
    "noun.process", "noun.quantity", "noun.relation", "noun.shape", "noun.state",
    "noun.substance", "noun.time", "verb.body", "verb.change", "verb.cognition",
    "verb.communication", "verb.competition", "verb.consumption", "verb.contact",
    "verb.creation", "verb.emotion", "verb.motion", "verb.perception", "verb.possession",
    "verb.social", "verb.stative", "verb.weather", "adj.ppl",
]

# Parts of speech in the order the words and exceptions files use.
POS_LETTERS = "nvar"
EXC_FILES = {"n": "noun.exc", "v": "verb.exc", "a": "adj.exc", "r": "adv.exc"}


class DataError(Exception):
    """A WordNet file is missing or not in the documented format."""


def lemma_text(word):
    """WordNet writes multiword lemmas with underscores; the data set uses spaces."""
    return word.lower().replace("_", " ")


def data_lines(path):
    """Lines of a WordNet index or data file without the licence header (lines starting
    with two spaces)."""
    with open(path, encoding="ascii") as f:
        for line in f:
            if not line.startswith("  "):
                yield line.rstrip("\n")


def read_data_noun(path):
    """data.noun -> {offset: (lexfile, [words in synset order], [hypernyms], [instances])}."""
    synsets = {}
    for line in data_lines(path):
        head = line.split(" | ", 1)[0].split()
        offset, lexfile, ss_type = int(head[0]), int(head[1]), head[2]
        if ss_type != "n":
            raise DataError(f"data.noun: synset {head[0]} has type {ss_type}")
        w_cnt = int(head[3], 16)
        words = []
        for i in range(w_cnt):
            words.append((head[4 + 2 * i], int(head[5 + 2 * i], 16)))
        at = 4 + 2 * w_cnt
        p_cnt = int(head[at])
        hyper, inst = [], []
        for i in range(p_cnt):
            sym, target, pos, _src = head[at + 1 + 4 * i : at + 5 + 4 * i]
            if sym == "@" and pos == "n":
                hyper.append(int(target))
            elif sym == "@i" and pos == "n":
                inst.append(int(target))
        synsets[offset] = (lexfile, words, hyper, inst)
    return synsets


def read_index(path, pos):
    """index.<pos> -> [(lemma, [synset offsets in sense order])] in file order."""
    out = []
    for line in data_lines(path):
        f = line.split()
        if f[1] != pos:
            raise DataError(f"{os.path.basename(path)}: {f[0]} has pos {f[1]}")
        synset_cnt, p_cnt = int(f[2]), int(f[3])
        offsets = [int(x) for x in f[4 + p_cnt + 2 :]]
        if len(offsets) != synset_cnt:
            raise DataError(f"{os.path.basename(path)}: {f[0]}: {len(offsets)} != {synset_cnt}")
        out.append((f[0], offsets))
    return out


def read_noun_counts(path, sense_offsets):
    """cntlist.rev -> ({(lemma, offset): tag count} for noun senses, number of stale keys).

    A noun sense key is `lemma%1:lexfile:lex_id::`; `sense_offsets` maps
    (lemma, lexfile, lex_id) to the synset offset, built from data.noun. The packaged
    cntlist.rev holds a few hundred noun keys of senses that data.noun no longer has
    ("a%1:14:00::"); like NLTK, those count for nothing."""
    counts = {}
    stale = 0
    with open(path, encoding="ascii") as f:
        for line in f:
            key, _sense_number, count = line.split()
            lemma, rest = key.split("%", 1)
            parts = rest.split(":")
            if parts[0] != "1":
                continue
            offset = sense_offsets.get((lemma, int(parts[1]), int(parts[2])))
            if offset is None:
                stale += 1
                continue
            counts[(lemma, offset)] = int(count)
    return counts, stale


def read_exceptions(path):
    """An .exc file -> [(inflected, [base forms])]."""
    out = []
    with open(path, encoding="ascii") as f:
        for line in f:
            f_ = line.split()
            if len(f_) < 2:
                raise DataError(f"{os.path.basename(path)}: bad line {line!r}")
            out.append((lemma_text(f_[0]), [lemma_text(b) for b in f_[1:]]))
    return out


def derive(wn):
    """All four data files as text."""
    synsets = read_data_noun(os.path.join(wn, "data.noun"))
    offsets = sorted(synsets)
    ids = {off: i for i, off in enumerate(offsets)}

    sense_offsets = {}
    for off, (lexfile, words, _, _) in synsets.items():
        for word, lex_id in words:
            sense_offsets[(word.lower(), lexfile, lex_id)] = off
    counts, stale = read_noun_counts(os.path.join(wn, "cntlist.rev"), sense_offsets)

    # nouns: lemma TAB senses, a sense = id[,count[,position of the lemma in the synset]].
    noun_rows = []
    n_senses = 0
    for lemma, offs in read_index(os.path.join(wn, "index.noun"), "n"):
        senses = []
        for off in offs:
            if off not in synsets:
                raise DataError(f"index.noun: {lemma} names missing synset {off}")
            words = [w.lower() for w, _ in synsets[off][1]]
            if lemma not in words:
                raise DataError(f"index.noun: {lemma} is not a word of synset {off}")
            fields = [str(ids[off]), str(counts.get((lemma, off), 0)), str(words.index(lemma))]
            while len(fields) > 1 and fields[-1] == "0":
                fields.pop()
            senses.append(",".join(fields))
        n_senses += len(senses)
        noun_rows.append((lemma_text(lemma), " ".join(senses)))
    noun_rows.sort()
    nouns = "".join(f"{lemma}\t{senses}\n" for lemma, senses in noun_rows)

    # synsets: line i is synset id i: lexfile TAB hypernym ids TAB instance hypernym ids.
    syn_lines = ["lexnames\t" + "\t".join(LEXNAMES) + "\n"]
    for off in offsets:
        lexfile, _, hyper, inst = synsets[off]
        h = " ".join(str(ids[x]) for x in hyper)
        i = " ".join(str(ids[x]) for x in inst)
        syn_lines.append(f"{lexfile}\t{h}\t{i}\n")
    synset_text = "".join(syn_lines)

    # words: lemma TAB parts of speech among v, a, r.
    pos_of = {}
    for letter, name in (("v", "verb"), ("a", "adj"), ("r", "adv")):
        for lemma, _ in read_index(os.path.join(wn, f"index.{name}"), letter):
            pos_of.setdefault(lemma_text(lemma), set()).add(letter)
    words = "".join(
        f"{lemma}\t{''.join(p for p in POS_LETTERS if p in pos)}\n"
        for lemma, pos in sorted(pos_of.items())
    )

    # exceptions: pos TAB inflected TAB base [TAB base...]. A few forms have two lines
    # ("aurar eyir", "aurar eyrir"); one line per form holds all their bases in file order.
    merged = {}
    for letter in POS_LETTERS:
        for form, bases in read_exceptions(os.path.join(wn, EXC_FILES[letter])):
            known = merged.setdefault((POS_LETTERS.index(letter), form), [])
            known.extend(b for b in bases if b not in known)
    exc_rows = sorted((p, form, bases) for (p, form), bases in merged.items())
    exceptions = "".join(
        f"{POS_LETTERS[p]}\t{form}\t" + "\t".join(bases) + "\n" for p, form, bases in exc_rows
    )

    stats = {
        "noun lemmas": len(noun_rows),
        "noun senses": n_senses,
        "noun synsets": len(offsets),
        "tagged senses": len(counts),
        "stale count keys": stale,
        "other lemmas": len(pos_of),
        "exceptions": len(exc_rows),
    }
    files = {
        "nouns.tsv": nouns,
        "synsets.tsv": synset_text,
        "words.tsv": words,
        "exceptions.tsv": exceptions,
    }
    return files, stats


def licence_text(copyright_path):
    """The `Files: *` stanza of the Debian copyright file: the WordNet 3.0 licence and its
    copyright notice, verbatim (the debian/* stanza covers only the packaging)."""
    with open(copyright_path, encoding="utf-8") as f:
        stanzas = f.read().split("\n\n")
    for s in stanzas:
        if s.startswith("Files: *\n") and "License: WordNet3.0" in s:
            return s.rstrip("\n") + "\n"
    raise DataError(f"{copyright_path}: no `Files: *` stanza with the WordNet3.0 licence")


README = """\
# WordNet 3.0, derived data

Compact extract of Princeton WordNet 3.0 read by `src/words/wordnet.rs`. WordNet 3.0
Copyright 2006 by Princeton University; the licence is in `LICENSE` (copied verbatim from
the copyright file of Debian's `wordnet-base` package) and must accompany every copy.

Derived by `scripts/wordnet_data.py` from the package's index.noun, data.noun, index.verb,
index.adj, index.adv, noun.exc, verb.exc, adj.exc, adv.exc and cntlist.rev. Regenerate with

    python3 scripts/wordnet_data.py

(uses /usr/share/wordnet when installed, otherwise `apt-get download wordnet-base` into a
temporary directory). The script is deterministic; the .zlib bytes also depend on the zlib
version, the text inside does not.

Each `*.tsv.zlib` file is one zlib stream of UTF-8 text, one record per line, fields separated
by tabs. Lemmas are lower case with spaces between words ("coffee table"). To read one:

    python3 -c 'import sys,zlib;sys.stdout.write(zlib.decompress(open(sys.argv[1],"rb").read()).decode())' nouns.tsv.zlib

| file | line | content |
| --- | --- | --- |
| `nouns.tsv.zlib` | `lemma TAB sense sense ...` | every noun lemma, sorted by bytes; its senses in WordNet sense order (index.noun), a sense being `id[,count[,position]]`: synset id, tag count from cntlist.rev (0 when absent or omitted), the lemma's position among its synset's words (0 when omitted) |
| `synsets.tsv.zlib` | first line `lexnames TAB name...`; then one line per synset in id order: `lexfile TAB hypernyms TAB instance hypernyms` | lexnames(5WN) by number; every noun synset, ids numbered in data.noun offset order; lexfile indexes the lexnames; hypernyms (`@`) and instance hypernyms (`@i`) are space-separated synset ids |
| `words.tsv.zlib` | `lemma TAB pos` | every verb, adjective and adverb lemma, sorted; pos lists `v`, `a`, `r` |
| `exceptions.tsv.zlib` | `pos TAB inflected TAB base [TAB base...]` | the morphological exception lists (`n`, `v`, `a`, `r`), sorted |

Synset ids are this data set's own (dense, 0-based); they are not WordNet byte offsets. Name
synsets NLTK-style instead ("artifact.n.01").

Tag counts are looked up by sense key, as NLTK does. The packaged cntlist.rev holds 265 noun
keys whose senses data.noun does not have ("a%1:14:00::"); they are dropped, and its
sense-number column, which disagrees with index.noun for 153 keys, is not used.
"""


def write_outputs(out, files, licence):
    os.makedirs(out, exist_ok=True)
    sizes = {}
    for name, text in files.items():
        raw = text.encode("utf-8")
        packed = zlib.compress(raw, 9)
        path = os.path.join(out, name + ".zlib")
        with open(path, "wb") as f:
            f.write(packed)
        sizes[name] = (len(raw), len(packed))
    for name, text in (("LICENSE", licence), ("README.md", README)):
        with open(os.path.join(out, name), "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
    return sizes


def find_copyright(root):
    path = os.path.join(root, "usr", "share", "doc", PACKAGE, "copyright")
    if not os.path.isfile(path):
        raise DataError(f"no copyright file at {path}")
    return path


def run(root, out):
    wn = os.path.join(root, "usr", "share", "wordnet")
    files, stats = derive(wn)
    licence = licence_text(find_copyright(root))
    sizes = write_outputs(out, files, licence)
    raw = sum(r for r, _ in sizes.values())
    packed = sum(p for _, p in sizes.values())
    parts = ", ".join(f"{v} {k}" for k, v in stats.items())
    files_ = ", ".join(f"{k}.zlib {p / 1e3:.0f} kB" for k, (_, p) in sizes.items())
    print(f"wordnet: {parts}; {files_}; total {packed / 1e6:.2f} MB ({raw / 1e6:.2f} MB text) in {os.path.relpath(out, ROOT)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    ap.add_argument("--root", help="extracted package root holding usr/share/wordnet")
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory")
    args = ap.parse_args()
    try:
        if args.root:
            run(args.root, args.out)
        elif os.path.isfile("/usr/share/wordnet/index.noun"):
            run("/", args.out)
        else:
            with tempfile.TemporaryDirectory(prefix="wordnet-") as tmp:
                # apt fetches as its unprivileged _apt user and warns when that user cannot
                # write here; without such a user (or as non-root) the warning is harmless.
                try:
                    shutil.chown(tmp, user="_apt")
                except (LookupError, PermissionError):
                    pass
                subprocess.run(["apt-get", "download", PACKAGE], cwd=tmp, check=True,
                               stdout=subprocess.DEVNULL)
                debs = sorted(glob.glob(os.path.join(tmp, f"{PACKAGE}_*.deb")))
                if len(debs) != 1:
                    raise DataError(f"apt-get download left {len(debs)} {PACKAGE} packages")
                root = os.path.join(tmp, "root")
                subprocess.run(["dpkg-deb", "-x", debs[0], root], check=True)
                run(root, args.out)
    except (DataError, OSError, subprocess.CalledProcessError) as e:
        sys.exit(f"wordnet_data: {e}")


if __name__ == "__main__":
    main()
