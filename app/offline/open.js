/* The offline page's opening: Bokeh's document is built from its JSON, handed to the page,
 * and only then are its views built, laid out and painted -- so the first paint shows the
 * page's first contact, not the pack-time data painted once and then again.
 *
 *   MicropillarOpen(onDocument);
 *       // onDocument(doc) -> a Promise (or nothing): called once the document is built and
 *       // before its views are; they are built when the Promise settles
 *
 * It takes the place of ``Bokeh.embed.embed_items`` for the page's one call of it (the
 * script Bokeh writes into the page calls it when the page's HTML has been read: after
 * the page's own scripts), doing what it does with BokehJS's public pieces:
 * ``Document.from_json`` and ``embed.add_document_standalone``. Without those (another
 * BokehJS) the page gets the document once Bokeh has drawn it, as before.
 */
(function (root) {
  "use strict";

  /** Bokeh writes the documents' JSON HTML-escaped into the page (bokeh.embed.elements). */
  function unescape(s) {
    var entities = {amp: "&", lt: "<", gt: ">", quot: '"', "#x27": "'", "#x60": "`"};
    return s.replace(/&(amp|lt|gt|quot|#x27|#x60);/g, function (_, e) { return entities[e]; });
  }
  function element(id) { return id == null ? document.body : document.getElementById(id); }

  function poll(onDocument) {  // the document once Bokeh has built it (and drawn it)
    var B = root.Bokeh;
    if (B && B.documents && B.documents.length) onDocument(B.documents[0]);
    else setTimeout(function () { poll(onDocument); }, 5);
  }

  root.MicropillarOpen = function (onDocument) {
    var B = root.Bokeh, Document = null;
    try { Document = B.require("document").Document; } catch (error) { Document = null; }
    if (!Document || !Document.from_json || !B.embed || !B.embed.add_document_standalone) {
      poll(onDocument);
      return;
    }
    var embed = B.embed.embed_items;
    B.embed.embed_items = function (docsJson, renderItems) {
      B.embed.embed_items = embed;  // once: the page's own call
      if (typeof docsJson === "string") docsJson = JSON.parse(unescape(docsJson));
      var docs = {};
      Object.keys(docsJson).forEach(function (id) { docs[id] = Document.from_json(docsJson[id]); });
      return Promise.resolve(onDocument(docs[Object.keys(docs)[0]]))  // the page's one
        .catch(function (error) { console.error(error); })
        .then(function () {
          return renderItems.reduce(function (done, item) {
            return done.then(function (views) {
              var roots = (item.root_ids || []).map(function (r) { return element(item.roots[r]); });
              return B.embed.add_document_standalone(docs[item.docid], element(item.elementid),
                                                     roots, item.use_for_title)
                .then(function (view) { return views.concat([view]); });
            });
          }, Promise.resolve([]));
        });
    };
  };
}(this));
