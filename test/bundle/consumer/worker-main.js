/* global Worker */
// The page side of the Worker consumer: hands a canvas to a module Worker as an OffscreenCanvas
// (transferControlToOffscreen) and waits for the worker's report.
function renderInWorker(canvas, options) {
  const offscreen = canvas.transferControlToOffscreen();
  const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  return new Promise((resolve, reject) => {
    worker.onmessage = (event) => (event.data.error ? reject(new Error(event.data.error)) : resolve(event.data));
    worker.onerror = (event) => reject(new Error(event.message));
    worker.postMessage({ canvas: offscreen, ...options }, [offscreen]);
  });
}

window.renderInWorker = renderInWorker;
window.ready = true;
