"""The web floor the monitor's and the studio's servers share: who may reach them
(:mod:`.guard`), how they start (:mod:`.serving`), requests checked against a typed schema
(:mod:`.schema`), the routes' common answers (:mod:`.routes`) and the diagram script both
pages load (``page/diagram.js``)."""
