/* report_assets.h — report.html's style sheet and script: reports/report.css
 * and reports/report.js, embedded at build time by cmake/embed_text.cmake
 * (the report opens offline, with nothing beside it).
 */
#ifndef REPORTS_REPORT_ASSETS_H
#define REPORTS_REPORT_ASSETS_H

extern const char report_assets_css[];
/* Click a column header to sort by it (numbers numerically), filter rows,
 * show all columns, flip an image to its reference, step through a path's
 * filmstrip and flip its view (← →, F); the content is complete without
 * it (every image is also a link). */
extern const char report_assets_js[];

#endif
