"""SCXML (W3C State Chart XML) as LightRocks reads it: the vocabulary that the SCXML target
and the reader share (:mod:`languages.scxml.markup`) and the reader
(:mod:`languages.scxml.reader`), registered as the ``scxml-to-lr`` conversion.

SCXML is an interchange language here, not a language of the workbench: ``check`` and the
model path do not read ``.scxml`` files, ``lightrocks convert`` turns one into a LightRocks
statechart. It sits on the languages floor, beside UML/P, so that the target that writes
SCXML (:mod:`generators.scxml`) builds on it as every generator builds on its languages.
"""
