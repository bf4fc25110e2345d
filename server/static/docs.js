// /docs: Swagger UI on /openapi.json, from the copy this server ships (static/swagger-ui),
// so it renders offline and under the page's Content-Security-Policy (no inline script).
"use strict";

(function () {
  const target = document.getElementById("swagger-ui");
  if (typeof window.SwaggerUIBundle !== "function") {
    target.textContent = "Swagger UI did not load; the API description is at /openapi.json.";
    return;
  }
  window.ui = window.SwaggerUIBundle({
    url: "/openapi.json",
    dom_id: "#swagger-ui",
    deepLinking: true,
    layout: "BaseLayout",
    presets: [window.SwaggerUIBundle.presets.apis],
    validatorUrl: null, // never ask validator.swagger.io
    defaultModelsExpandDepth: 0,
  });
})();
